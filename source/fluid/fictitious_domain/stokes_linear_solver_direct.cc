// Method = direct: StokesSolver's linear systems by one factorisation per
// solve.

#include "stokes_linear_solvers.h"

namespace Fidus
{
  template <int dim>
  void
  StokesSolver<dim>::DirectLinearSolver::prepare_mesh()
  {
    // The lowest unconstrained pressure (hanging and periodic pressures
    // are constrained), the same on every rank.
    StokesSolver<dim>            &s     = this->solver;
    const types::global_dof_index n_u   = s.owned_partitioning[0].size();
    types::global_dof_index       first = numbers::invalid_dof_index;
    for (const auto i : s.owned_partitioning[1])
      if (!s.constraints.is_constrained(n_u + i))
        {
          first = i;
          break;
        }
    pinned_pressure = Utilities::MPI::min(first, s.mpi_communicator);
  }



  template <int dim>
  void
  StokesSolver<dim>::DirectLinearSolver::setup(const SolidIndicator<dim> &,
                                               const Function<dim> *)
  {
    // The first solve on a mesh copies the pattern and analyses it; later
    // ones copy values and factorise (a new mesh gets a new solver).
    StokesSolver<dim> &s = this->solver;
    if (direct)
      direct->refactorise();
    else
      direct = std::make_unique<DirectStokesSolver>(s.system_matrix,
                                                    s.owned_partitioning,
                                                    pinned_pressure,
                                                    s.mpi_communicator);
  }



  template <int dim>
  unsigned int
  StokesSolver<dim>::DirectLinearSolver::solve(Statistics &, double)
  {
    // Exact to round-off whatever the loop asks (an inexact Uzawa
    // tolerance saves nothing here): held to the linear tolerance.
    StokesSolver<dim> &s = this->solver;
    direct->solve(s.distributed_solution, s.rhs, s.settings.linear_tolerance);
    s.constraints.distribute(s.distributed_solution);
    s.solution = s.distributed_solution;
    return 0;
  }



  template class StokesSolver<2>::DirectLinearSolver;
  template class StokesSolver<3>::DirectLinearSolver;
} // namespace Fidus
