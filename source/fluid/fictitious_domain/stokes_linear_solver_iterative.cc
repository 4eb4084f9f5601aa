// FGMRES with the block Schur preconditioner: what StokesSolver's AMG and
// GMG choices share (the pressure Jacobi, the rigid-body correction, the
// solve itself).

#include "stokes_linear_solvers.h"

#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/vector_memory.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/block_schur_preconditioner.h>
#include <fidus/fluid/fictitious_domain/deflated_velocity_preconditioner.h>
#include <fidus/fluid/fictitious_domain/stokes_operator.h>
#include <iostream>
#include <sstream>

namespace Fidus
{



  template <int dim>
  void
  StokesSolver<dim>::IterativeLinearSolver::setup(
    const SolidIndicator<dim> &solid,
    const Function<dim>       *fluid_viscosity)
  {
    StokesSolver<dim> &s = this->solver;
    jacobi.initialize(s.preconditioner_matrix.block(1, 1));
    update_velocity_preconditioner(solid, fluid_viscosity);
    if (this->assembles_velocity_block())
      velocity_block =
        std::make_unique<VelocityBlock>(s.system_matrix.block(0, 0));
    else
      velocity_block = matrix_free_velocity_block();
    build_rigid_body_correction(solid);
    report_setup();
    // Once per mesh (this object is new on each), when its system and
    // preconditioners first hold their memory.
    if (restart == 0)
      fit_restart();
    if (s.settings.verbose &&
        Utilities::MPI::this_mpi_process(s.mpi_communicator) == 0)
      std::cout << "    rigid-body correction: "
                << (rigid_body_correction.empty() ? "off" : "on") << ", set-up "
                << rigid_body_correction.setup_seconds << " s" << std::endl;
  }



  template <int dim>
  template <class VelocityPreconditioner>
  unsigned int
  StokesSolver<dim>::IterativeLinearSolver::fgmres(
    Statistics                   &stats,
    const VelocityPreconditioner &velocity,
    const double                  tolerance)
  {
    StokesSolver<dim> &s        = this->solver;
    const double       rhs_norm = s.rhs.l2_norm();
    if (rhs_norm == 0.)
      {
        s.distributed_solution = 0;
        s.constraints.distribute(s.distributed_solution);
        s.solution = s.distributed_solution;
        return 0;
      }
    const double target = tolerance * rhs_norm;

    // Every solve starts from zero, not from the last velocity. The last
    // velocity is rigid on the previous particle positions or for the
    // previous multiplier, so its residual sits at the interfaces: the
    // content that the pressure-mass Schur approximation handles worst.
    // From zero, the residual is the smooth right-hand side. Measured
    // (doc/performance.md): 2D paper scene to t = 3, level 6: 4576 -> 3079
    // FGMRES iterations; second Uzawa solve of the 2D inclusion: 270 -> 92.
    s.distributed_solution = 0;

    unsigned int iterations = 0;
    stats.gmres_restart     = restart;
    SolverFGMRES<TrilinosWrappers::MPI::BlockVector>::AdditionalData data(
      restart);
    // One FGMRES run from the current iterate, the velocity block solved by
    // one V-cycle (cheap) or by inner CG (expensive); returns whether it
    // reached the target, with its last residual in @p residual.
    const auto run = [&](const unsigned int max_steps,
                         const bool         expensive,
                         double            &residual) {
      SolverControl control(max_steps, target, false, false);
      const BlockSchurPreconditioner<VelocityPreconditioner> preconditioner(
        s.system_matrix,
        *velocity_block,
        s.preconditioner_matrix.block(1, 1),
        velocity,
        jacobi,
        expensive);
      bool converged = true;
      try
        {
          SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(control,
                                                                  data);
          solver.solve(StokesOperator(s.system_matrix, *velocity_block),
                       s.distributed_solution,
                       s.rhs,
                       preconditioner);
        }
      catch (const SolverControl::NoConvergence &)
        {
          converged = false;
        }
      iterations += control.last_step();
      // The basis goes back to deal.II's vector pool, which would keep it
      // for the rest of the run (two vectors of the system per iteration:
      // 640 MB per rank for 131 iterations of the 3D bulk scene at level
      // 5); the next solve allocates what it needs.
      GrowingVectorMemory<
        TrilinosWrappers::MPI::BlockVector>::release_unused_memory();
      if (expensive)
        stats.inner_iterations += preconditioner.inner_iterations;
      residual = control.last_value();
      return converged;
    };

    double residual = 0.;
    if (s.settings.max_cheap_iterations > 0 &&
        run(s.settings.max_cheap_iterations, false, residual))
      {
        s.constraints.distribute(s.distributed_solution);
        s.solution = s.distributed_solution;
        return iterations;
      }
    ++stats.expensive_solves;
    const unsigned int before = iterations;
    if (!run(s.settings.max_linear_iterations, true, residual))
      {
        std::ostringstream m;
        m << "the Stokes solver (FGMRES) did not converge in "
          << iterations - before << " iterations: residual " << residual
          << " > target " << target
          << " (Fluid/Linear solver/Tolerance = " << s.settings.linear_tolerance
          << ", this solve's tolerance " << tolerance
          << "); try more 'Maximum iterations' or a smaller 'Penalty "
             "factor'";
        throw RunError(m.str());
      }
    s.constraints.distribute(s.distributed_solution);
    s.solution = s.distributed_solution;
    return iterations;
  }



  template <int dim>
  void
  StokesSolver<dim>::IterativeLinearSolver::build_rigid_body_correction(
    const SolidIndicator<dim> &solid)
  {
    const StokesSolver<dim>  &s = this->solver;
    std::vector<unsigned int> rows, particles;
    std::vector<double>       values;
    const unsigned int        n_modes = dim == 2 ? 3 : 6;
    if (s.settings.rigid_body_correction && solid.n_particles() > 0)
      {
        // The rigid motions of entry e (a particle or one of its periodic
        // images: the rotation is about the centre of the piece the DoF
        // belongs to) at the support points of the owned velocity DoFs.
        const Quadrature<dim> support(s.fe.get_unit_support_points());
        FEValues<dim> fe_support(s.fe, support, update_quadrature_points);
        std::vector<types::global_dof_index> dofs(s.fe.n_dofs_per_cell());
        std::vector<bool> done(s.solid_entry_of_dof.size(), false);
        for (const auto &cell : s.cells)
          {
            if (!cell->is_locally_owned() && !cell->is_ghost())
              continue;
            cell->get_dof_indices(dofs);
            bool any = false;
            for (unsigned int k = 0; k < dofs.size() && !any; ++k)
              any =
                s.fe.system_to_component_index(k).first < dim &&
                s.owned_partitioning[0].is_element(dofs[k]) &&
                !done[s.owned_partitioning[0].index_within_set(dofs[k])] &&
                s.solid_entry_of_dof[s.owned_partitioning[0].index_within_set(
                  dofs[k])] >= 0;
            if (!any)
              continue;
            fe_support.reinit(cell);
            for (unsigned int k = 0; k < dofs.size(); ++k)
              {
                const unsigned int c = s.fe.system_to_component_index(k).first;
                if (c >= dim || !s.owned_partitioning[0].is_element(dofs[k]) ||
                    s.constraints.is_constrained(dofs[k]))
                  continue;
                const unsigned int i =
                  s.owned_partitioning[0].index_within_set(dofs[k]);
                if (done[i] || s.solid_entry_of_dof[i] < 0)
                  continue;
                done[i]                = true;
                const unsigned int   e = s.solid_entry_of_dof[i];
                const Tensor<1, dim> x =
                  fe_support.quadrature_point(k) - solid.center(e);
                rows.push_back(i);
                particles.push_back(solid.owner(e));
                append_rigid_modes(c, x, values);
              }
          }
      }
    rigid_body_correction.reinit(*velocity_block,
                                 s.owned_partitioning[0],
                                 s.mpi_communicator,
                                 s.settings.rigid_body_correction ?
                                   solid.n_particles() :
                                   0,
                                 n_modes,
                                 std::move(rows),
                                 std::move(particles),
                                 std::move(values));
  }



  template class StokesSolver<2>::IterativeLinearSolver;
  template class StokesSolver<3>::IterativeLinearSolver;

  // The velocity preconditioners of the derived classes.
  template unsigned int
  StokesSolver<2>::IterativeLinearSolver::fgmres(
    Statistics &,
    const DeflatedVelocityPreconditioner<TrilinosWrappers::PreconditionAMG> &,
    double);
  template unsigned int
  StokesSolver<3>::IterativeLinearSolver::fgmres(
    Statistics &,
    const DeflatedVelocityPreconditioner<TrilinosWrappers::PreconditionAMG> &,
    double);
  template unsigned int
  StokesSolver<2>::IterativeLinearSolver::fgmres(
    Statistics &,
    const DeflatedVelocityPreconditioner<VelocityMultigrid<2>> &,
    double);
  template unsigned int
  StokesSolver<3>::IterativeLinearSolver::fgmres(
    Statistics &,
    const DeflatedVelocityPreconditioner<VelocityMultigrid<3>> &,
    double);
} // namespace Fidus
