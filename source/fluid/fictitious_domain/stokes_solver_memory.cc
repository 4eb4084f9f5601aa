// What the fictitious domain's iterative solvers need in memory, checked
// against the ranks' budget before a mesh's system is built and before
// FGMRES builds its basis.

#include "stokes_linear_solvers.h"

#include <algorithm>
#include <cmath>
#include <deal.II/base/mpi.h>
#include <fidus/core/input_error.h>
#include <fidus/core/memory_usage.h>
#include <sstream>

namespace Fidus
{
  namespace
  {
    /// The smallest restart worth running: below it FGMRES's count grows
    /// fast (a 2D pair: 104 iterations with 200, 170 with 10).
    constexpr unsigned int smallest_restart = 10;

    /// FGMRES's own work vectors besides the basis.
    constexpr double work_vectors = 3.;

    /// Vectors of the system FGMRES holds with restart @p r: the basis and
    /// the preconditioned basis, and its work vectors.
    double
    basis_vectors(const unsigned int r)
    {
      return 2. * r + work_vectors;
    }

    /// Vectors of the system the accelerated Uzawa loop keeps beside
    /// FGMRES's (Fluid/Uzawa acceleration depth m): m + 1 multipliers and
    /// m + 1 velocities, and one to import them into.
    double
    acceleration_vectors(const unsigned int depth)
    {
      return depth == 0 ? 0. : 2. * (depth + 1.) + 1.;
    }
  } // namespace



  template <int dim>
  void
  StokesSolver<dim>::check_memory_for_mesh(
    const types::global_dof_index n_owned) const
  {
    // Bytes per owned unknown of the system, its preconditioner and the
    // solver's vectors, measured on the 3D bulk scene (573 spheres, levels
    // 4 and 5, 2 ranks; doc/cookbooks/cluster.md): about 1.8-2.1 KB with the
    // matrix-free GMG, 12.5 KB with an assembled Q2 velocity block and its
    // AMG. The lower ends, so that a run is stopped only when it would
    // clearly not fit.
    const bool matrix_free =
      settings.geometric_multigrid && settings.matrix_free_velocity_block;
    const double per_unknown = matrix_free ? 1.8e3 : 12.5e3;
    const double needed =
      double(n_owned) *
      (per_unknown +
       8. * (basis_vectors(std::min(settings.gmres_restart, smallest_restart)) +
             acceleration_vectors(settings.uzawa_acceleration_depth)));
    const double free = memory_budget.free_bytes();
    const double short_by =
      Utilities::MPI::max(needed - free, mpi_communicator);
    if (!(short_by > 0.))
      return;
    std::ostringstream m;
    m << "the mesh has " << dof_handler.n_dofs() << " unknowns; its "
      << (matrix_free ? "matrix-free GMG" : "assembled velocity block")
      << " system with the smallest FGMRES basis needs about "
      << MemoryUsage::format(Utilities::MPI::max(needed, mpi_communicator))
      << " more on the largest rank (" << MemoryUsage::format(per_unknown)
      << " per unknown), but a rank has "
      << MemoryUsage::format(Utilities::MPI::min(free, mpi_communicator))
      << " left (" << memory_budget.source()
      << "): lower 'Mesh refinement/Maximum level', run on more machines, "
      << "or set 'Fluid/Linear solver/Memory per rank' if the machine's "
      << "figure is not what the run may use";
    throw RunError(m.str());
  }



  template <int dim>
  bool
  StokesSolver<dim>::basis_is_short() const
  {
    const double vector_bytes = 8. * double(owned_partitioning[0].n_elements() +
                                            owned_partitioning[1].n_elements());
    const double short_by =
      vector_bytes * (basis_vectors(settings.gmres_restart) +
                      acceleration_vectors(settings.uzawa_acceleration_depth)) -
      memory_budget.free_bytes();
    return Utilities::MPI::max(short_by, mpi_communicator) > 0.;
  }



  template <int dim>
  void
  StokesSolver<dim>::IterativeLinearSolver::fit_restart()
  {
    const StokesSolver<dim> &s = this->solver;
    const double             vector_bytes =
      8. * double(s.owned_partitioning[0].n_elements() +
                  s.owned_partitioning[1].n_elements());
    const double free = s.memory_budget.free_bytes();
    // The largest restart whose basis fits in what is left beside the
    // accelerated Uzawa loop's vectors (basis_vectors() solved for r).
    const double fits =
      std::isfinite(free) ?
        std::floor((free / vector_bytes - work_vectors -
                    acceleration_vectors(s.settings.uzawa_acceleration_depth)) /
                   2.) :
        double(s.settings.gmres_restart);
    restart = static_cast<unsigned int>(Utilities::MPI::min(
      std::max(0., std::min(fits, double(s.settings.gmres_restart))),
      s.mpi_communicator));
    if (restart >= std::min(s.settings.gmres_restart, smallest_restart))
      return;
    std::ostringstream m;
    m << "the system of this mesh (" << s.dof_handler.n_dofs()
      << " unknowns) is built, but a rank has "
      << MemoryUsage::format(Utilities::MPI::min(free, s.mpi_communicator))
      << " left (" << s.memory_budget.source() << "): FGMRES's basis fits "
      << restart << " iterations, fewer than " << smallest_restart
      << " (Fluid/Linear solver/GMRES restart); lower 'Mesh "
      << "refinement/Maximum level' or run on more machines";
    throw RunError(m.str());
  }



  template void
    StokesSolver<2>::check_memory_for_mesh(types::global_dof_index) const;
  template void
    StokesSolver<3>::check_memory_for_mesh(types::global_dof_index) const;
  template bool
  StokesSolver<2>::basis_is_short() const;
  template bool
  StokesSolver<3>::basis_is_short() const;
  template void
  StokesSolver<2>::IterativeLinearSolver::fit_restart();
  template void
  StokesSolver<3>::IterativeLinearSolver::fit_restart();
} // namespace Fidus
