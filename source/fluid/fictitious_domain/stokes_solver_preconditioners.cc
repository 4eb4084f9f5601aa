#include "stokes_solver_preconditioners.h"

#include <Teuchos_ParameterList.hpp>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>

namespace Fidus
{
  namespace
  {
    /// Component @p c of the rigid motions at offset @p x from the centre:
    /// the dim translations, then the rotations (about z in 2D; about x, y
    /// and z in 3D), appended to @p values.
    template <int dim>
    void
    append_rigid_modes(const unsigned int    c,
                       const Tensor<1, dim> &x,
                       std::vector<double>  &values)
    {
      for (unsigned int m = 0; m < dim; ++m)
        values.push_back(m == c ? 1. : 0.);
      if (dim == 2)
        values.push_back(c == 0 ? -x[1] : x[0]);
      else
        {
          // rotations about x, y, z: (0,-z,y), (z,0,-x), (-y,x,0)
          const double rot[3][3] = {{0, x[dim - 1], -x[1]},
                                    {-x[dim - 1], 0, x[0]},
                                    {x[1], -x[0], 0}};
          for (unsigned int m = 0; m < 3; ++m)
            values.push_back(rot[c][m]);
        }
    }
  } // namespace



  template <int dim>
  void
  StokesSolver<dim>::setup_preconditioners(const SolidIndicator<dim> &solid,
                                           const Function<dim> *fluid_viscosity)
  {
    preconditioners->jacobi.initialize(preconditioner_matrix.block(1, 1));
    if (multigrid_active)
      {
        std::vector<unsigned int> candidates;
        preconditioners->multigrid->update(
          [&](const typename Triangulation<dim>::cell_iterator &cell,
              const bool,
              const std::vector<Point<dim>> &points,
              std::vector<double>           &eta) {
            solid.candidates(cell->center(),
                             0.5 * cell->diameter(),
                             candidates);
            viscosity_at(solid,
                         fluid_viscosity,
                         candidates,
                         is_shared_cell(solid, cell, candidates),
                         points,
                         eta);
          },
          velocity_block_assembled() ? &system_matrix.block(0, 0) : nullptr,
          constraints);
      }
    else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
        amg_data.elliptic              = true;
        amg_data.higher_order_elements = true;
        amg_data.smoother_sweeps       = settings.amg_smoother_sweeps;
        amg_data.smoother_type         = settings.amg_smoother_type.c_str();
        amg_data.aggregation_threshold = settings.amg_aggregation_threshold;
        // Near-null space of the velocity block: translations and rotations.
        // The solid is r times more viscous than the fluid, so the AMG coarse
        // spaces must contain the rigid motions that leave the solid
        // unstrained; translations alone (the usual constant modes) make the
        // iteration count grow with r.
        const Epetra_Map &row_map =
          system_matrix.block(0, 0).trilinos_matrix().RowMap();
        const unsigned int n_modes = dim == 2 ? 3 : 6;
        preconditioners->rigid_modes =
          std::make_unique<Epetra_MultiVector>(row_map, n_modes);
        Epetra_MultiVector &modes = *preconditioners->rigid_modes;
        std::vector<double> values;
        Point<dim>          centre;
        for (unsigned int d = 0; d < dim; ++d)
          centre[d] = 0.5;
        {
          const Quadrature<dim> support(fe.get_unit_support_points());
          FEValues<dim> fe_support(fe, support, update_quadrature_points);
          std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              {
                fe_support.reinit(cell);
                cell->get_dof_indices(dofs);
                for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
                  {
                    const unsigned int c =
                      fe.system_to_component_index(k).first;
                    if (c >= dim)
                      continue;
                    const int lid = row_map.LID(
                      static_cast<TrilinosWrappers::types::int_type>(dofs[k]));
                    if (lid < 0)
                      continue;
                    const Tensor<1, dim> x =
                      fe_support.quadrature_point(k) - centre;
                    values.clear();
                    append_rigid_modes<dim>(c, x, values);
                    for (unsigned int m = 0; m < n_modes; ++m)
                      modes[m][lid] = values[m];
                  }
              }
        }
        Teuchos::ParameterList              ml_parameters;
        std::unique_ptr<Epetra_MultiVector> unused_modes;
        amg_data.set_parameters(ml_parameters,
                                unused_modes,
                                system_matrix.block(0, 0));
        ml_parameters.set("null space: type", "pre-computed");
        ml_parameters.set("null space: dimension", int(n_modes));
        ml_parameters.set("null space: vectors", modes.Values());
        preconditioners->amg.initialize(system_matrix.block(0, 0),
                                        ml_parameters);
      }
    if (velocity_block_assembled())
      velocity_block =
        std::make_unique<VelocityBlock>(system_matrix.block(0, 0));
    else
      velocity_block = std::make_unique<VelocityBlock>(
        [mg = preconditioners->multigrid.get()](
          TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) {
          mg->apply_velocity_block(dst, src);
        });
    build_rigid_body_correction(solid);
    if (multigrid_active)
      {
        // Two products with each level's operator: a check of the
        // hierarchy that costs a fraction of one V-cycle.
        const double defect   = preconditioners->multigrid->galerkin_defect();
        worst_galerkin_defect = std::max(worst_galerkin_defect, defect);
        if (settings.verbose &&
            Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          std::cout << "    multigrid: "
                    << preconditioners->multigrid->get_info().n_levels
                    << " levels, Galerkin defect " << defect
                    << ", smoother blocks (rank 0) "
                    << preconditioners->multigrid->get_info().smoother_blocks
                    << ", update "
                    << preconditioners->multigrid->get_info().update_seconds
                    << " s (viscosity "
                    << preconditioners->multigrid->get_info().viscosity_seconds
                    << ", diagonals "
                    << preconditioners->multigrid->get_info().diagonal_seconds
                    << ", blocks "
                    << preconditioners->multigrid->get_info().blocks_seconds
                    << ", coarse "
                    << preconditioners->multigrid->get_info().coarse_seconds
                    << ")" << std::endl;
      }
    if (settings.verbose &&
        Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::cout << "    rigid-body correction: "
                << (preconditioners->rigid_body_correction.empty() ? "off" :
                                                                     "on")
                << ", set-up "
                << preconditioners->rigid_body_correction.setup_seconds << " s"
                << std::endl;
  }



  template <int dim>
  void
  StokesSolver<dim>::build_rigid_body_correction(
    const SolidIndicator<dim> &solid)
  {
    std::vector<unsigned int> rows, particles;
    std::vector<double>       values;
    const unsigned int        n_modes = dim == 2 ? 3 : 6;
    if (settings.rigid_body_correction && solid.n_particles() > 0)
      {
        // The rigid motions of entry e (a particle or one of its periodic
        // images: the rotation is about the centre of the piece the DoF
        // belongs to) at the support points of the owned velocity DoFs.
        const Quadrature<dim> support(fe.get_unit_support_points());
        FEValues<dim>         fe_support(fe, support, update_quadrature_points);
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        std::vector<bool> done(solid_entry_of_dof.size(), false);
        for (const auto &cell : cells)
          {
            if (!cell->is_locally_owned() && !cell->is_ghost())
              continue;
            cell->get_dof_indices(dofs);
            bool any = false;
            for (unsigned int k = 0; k < dofs.size() && !any; ++k)
              any = fe.system_to_component_index(k).first < dim &&
                    owned_partitioning[0].is_element(dofs[k]) &&
                    !done[owned_partitioning[0].index_within_set(dofs[k])] &&
                    solid_entry_of_dof[owned_partitioning[0].index_within_set(
                      dofs[k])] >= 0;
            if (!any)
              continue;
            fe_support.reinit(cell);
            for (unsigned int k = 0; k < dofs.size(); ++k)
              {
                const unsigned int c = fe.system_to_component_index(k).first;
                if (c >= dim || !owned_partitioning[0].is_element(dofs[k]) ||
                    constraints.is_constrained(dofs[k]))
                  continue;
                const unsigned int i =
                  owned_partitioning[0].index_within_set(dofs[k]);
                if (done[i] || solid_entry_of_dof[i] < 0)
                  continue;
                done[i]                = true;
                const unsigned int   e = solid_entry_of_dof[i];
                const Tensor<1, dim> x =
                  fe_support.quadrature_point(k) - solid.center(e);
                rows.push_back(i);
                particles.push_back(solid.owner(e));
                append_rigid_modes<dim>(c, x, values);
              }
          }
      }
    preconditioners->rigid_body_correction.reinit(
      *velocity_block,
      owned_partitioning[0],
      mpi_communicator,
      settings.rigid_body_correction ? solid.n_particles() : 0,
      n_modes,
      std::move(rows),
      std::move(particles),
      std::move(values));
  }



  template void
  StokesSolver<2>::setup_preconditioners(const SolidIndicator<2> &,
                                         const Function<2> *);
  template void
  StokesSolver<3>::setup_preconditioners(const SolidIndicator<3> &,
                                         const Function<3> *);
  template void
  StokesSolver<2>::build_rigid_body_correction(const SolidIndicator<2> &);
  template void
  StokesSolver<3>::build_rigid_body_correction(const SolidIndicator<3> &);
} // namespace Fidus
