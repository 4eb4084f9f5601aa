// Preconditioner = AMG: StokesSolver's velocity block preconditioned by
// Trilinos ML with the rigid motions as its near-null space.

#include "stokes_linear_solvers.h"

#include <Teuchos_ParameterList.hpp>
#include <deal.II/fe/fe_values.h>
#include <fidus/fluid/fictitious_domain/deflated_velocity_preconditioner.h>

namespace Fidus
{



  template <int dim>
  void
  StokesSolver<dim>::AmgLinearSolver::update_velocity_preconditioner(
    const SolidIndicator<dim> &,
    const Function<dim> *)
  {
    const StokesSolver<dim>                          &s = this->solver;
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    amg_data.elliptic              = true;
    amg_data.higher_order_elements = true;
    amg_data.smoother_sweeps       = s.settings.amg_smoother_sweeps;
    amg_data.smoother_type         = s.settings.amg_smoother_type.c_str();
    amg_data.aggregation_threshold = s.settings.amg_aggregation_threshold;
    // Near-null space of the velocity block: translations and rotations.
    // The solid is r times more viscous than the fluid, so the AMG coarse
    // spaces must contain the rigid motions that leave the solid
    // unstrained; translations alone (the usual constant modes) make the
    // iteration count grow with r.
    const Epetra_Map &row_map =
      s.system_matrix.block(0, 0).trilinos_matrix().RowMap();
    const unsigned int n_modes = dim == 2 ? 3 : 6;
    rigid_modes = std::make_unique<Epetra_MultiVector>(row_map, n_modes);
    Epetra_MultiVector &modes = *rigid_modes;
    std::vector<double> values;
    Point<dim>          centre;
    for (unsigned int d = 0; d < dim; ++d)
      centre[d] = 0.5;
    {
      const Quadrature<dim> support(s.fe.get_unit_support_points());
      FEValues<dim>         fe_support(s.fe, support, update_quadrature_points);
      std::vector<types::global_dof_index> dofs(s.fe.n_dofs_per_cell());
      for (const auto &cell : s.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_support.reinit(cell);
            cell->get_dof_indices(dofs);
            for (unsigned int k = 0; k < s.fe.n_dofs_per_cell(); ++k)
              {
                const unsigned int c = s.fe.system_to_component_index(k).first;
                if (c >= dim)
                  continue;
                const int lid = row_map.LID(
                  static_cast<TrilinosWrappers::types::int_type>(dofs[k]));
                if (lid < 0)
                  continue;
                const Tensor<1, dim> x =
                  fe_support.quadrature_point(k) - centre;
                values.clear();
                IterativeLinearSolver::append_rigid_modes(c, x, values);
                for (unsigned int m = 0; m < n_modes; ++m)
                  modes[m][lid] = values[m];
              }
          }
    }
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> unused_modes;
    amg_data.set_parameters(ml_parameters,
                            unused_modes,
                            s.system_matrix.block(0, 0));
    ml_parameters.set("null space: type", "pre-computed");
    ml_parameters.set("null space: dimension", int(n_modes));
    ml_parameters.set("null space: vectors", modes.Values());
    amg.initialize(s.system_matrix.block(0, 0), ml_parameters);
  }



  template <int dim>
  unsigned int
  StokesSolver<dim>::AmgLinearSolver::solve(Statistics  &stats,
                                            const double tolerance)
  {
    return this->fgmres(
      stats,
      DeflatedVelocityPreconditioner<TrilinosWrappers::PreconditionAMG>(
        *this->velocity_block,
        amg,
        this->rigid_body_correction),
      tolerance);
  }



  template class StokesSolver<2>::AmgLinearSolver;
  template class StokesSolver<3>::AmgLinearSolver;
} // namespace Fidus
