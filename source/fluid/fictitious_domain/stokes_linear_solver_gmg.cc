// Preconditioner = GMG: StokesSolver's velocity block preconditioned (and,
// matrix-free, applied) by the geometric multigrid.

#include "stokes_linear_solvers.h"

#include <deal.II/base/utilities.h>
#include <fidus/core/memory_usage.h>
#include <fidus/fluid/fictitious_domain/deflated_velocity_preconditioner.h>
#include <iostream>

namespace Fidus
{
  template <int dim>
  StokesSolver<dim>::GmgLinearSolver::GmgLinearSolver(StokesSolver<dim> &s)
    : IterativeLinearSolver(s)
  {
    typename VelocityMultigrid<dim>::Settings mg;
    mg.degree          = s.settings.degree;
    mg.smoother_degree = s.settings.mg_smoother_degree;
    mg.smoother_blocks = s.settings.mg_smoother_blocks == "cut cells" ?
                           SmootherBlocks::cut_cells :
                           SmootherBlocks::none;
    mg.averaging       = VelocityMultigrid<dim>::parse_averaging(
      s.settings.mg_viscosity_averaging);
    multigrid = std::make_unique<VelocityMultigrid<dim>>(s.triangulation, mg);
    multigrid->setup(s.dof_handler, s.periodic_directions, s.dirichlet_ids);
  }



  template <int dim>
  bool
  StokesSolver<dim>::GmgLinearSolver::assembles_velocity_block() const
  {
    return !this->solver.settings.matrix_free_velocity_block;
  }



  template <int dim>
  void
  StokesSolver<dim>::GmgLinearSolver::setup(
    const SolidIndicator<dim> &solid,
    const Function<dim>       *fluid_viscosity)
  {
    IterativeLinearSolver::setup(solid, fluid_viscosity);
    if (assembles_velocity_block())
      return;
    // The assembly moves the known values of constrained DoFs (the boundary
    // velocity) to the right-hand side through the local matrices; without
    // the velocity-velocity part of those, the same load comes from the
    // matrix-free operator applied to the field of constrained values.
    StokesSolver<dim>                 &s = this->solver;
    TrilinosWrappers::MPI::BlockVector g(s.owned_partitioning,
                                         s.mpi_communicator);
    s.constraints.distribute(g);
    multigrid->subtract_constraint_load(s.base_rhs.block(0), g.block(0));
  }



  template <int dim>
  void
  StokesSolver<dim>::GmgLinearSolver::update_velocity_preconditioner(
    const SolidIndicator<dim> &solid,
    const Function<dim>       *fluid_viscosity)
  {
    StokesSolver<dim>        &s = this->solver;
    std::vector<unsigned int> candidates;
    multigrid->update(
      [&](const typename Triangulation<dim>::cell_iterator &cell,
          const bool,
          const std::vector<Point<dim>> &points,
          std::vector<double>           &eta) {
        solid.candidates(cell->center(), 0.5 * cell->diameter(), candidates);
        s.viscosity_at(solid,
                       fluid_viscosity,
                       candidates,
                       s.is_shared_cell(solid, cell, candidates),
                       points,
                       eta);
      },
      assembles_velocity_block() ? &s.system_matrix.block(0, 0) : nullptr,
      s.constraints);
    // The cut-cell blocks are summed as full matrices (tens of KB each,
    // on the heap) and kept packed; the full ones, freed, would stay
    // resident under the FGMRES basis that follows.
    MemoryUsage::release_free_memory();
  }



  template <int dim>
  std::unique_ptr<VelocityBlock>
  StokesSolver<dim>::GmgLinearSolver::matrix_free_velocity_block()
  {
    return std::make_unique<VelocityBlock>(
      [mg = multigrid.get()](TrilinosWrappers::MPI::Vector       &dst,
                             const TrilinosWrappers::MPI::Vector &src) {
        mg->apply_velocity_block(dst, src);
      });
  }



  template <int dim>
  void
  StokesSolver<dim>::GmgLinearSolver::report_setup()
  {
    // Two products with each level's operator: a check of the hierarchy
    // that costs a fraction of one V-cycle.
    StokesSolver<dim> &s      = this->solver;
    const double       defect = multigrid->galerkin_defect();
    s.worst_galerkin_defect   = std::max(s.worst_galerkin_defect, defect);
    if (s.settings.verbose &&
        Utilities::MPI::this_mpi_process(s.mpi_communicator) == 0)
      {
        const auto &info = multigrid->get_info();
        std::cout << "    multigrid: " << info.n_levels
                  << " levels, Galerkin defect " << defect
                  << ", smoother blocks (rank 0) " << info.smoother_blocks
                  << ", update " << info.update_seconds << " s (viscosity "
                  << info.viscosity_seconds << ", diagonals "
                  << info.diagonal_seconds << ", blocks " << info.blocks_seconds
                  << ", coarse " << info.coarse_seconds << ")" << std::endl;
      }
  }



  template <int dim>
  unsigned int
  StokesSolver<dim>::GmgLinearSolver::solve(Statistics  &stats,
                                            const double tolerance)
  {
    return this->fgmres(stats,
                        DeflatedVelocityPreconditioner<VelocityMultigrid<dim>>(
                          *this->velocity_block,
                          *multigrid,
                          this->rigid_body_correction),
                        tolerance);
  }



  template class StokesSolver<2>::GmgLinearSolver;
  template class StokesSolver<3>::GmgLinearSolver;
} // namespace Fidus
