// The Uzawa loop of StokesSolver (augmented Lagrangian for rigidity) and
// the FGMRES solve of each of its iterations; the rest of the class (DoFs,
// constraints, assembly, errors) is in stokes_solver.cc.
#include "stokes_solver_preconditioners.h"

#include <cmath>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/block_schur_preconditioner.h>
#include <fidus/fluid/deflated_velocity_preconditioner.h>
#include <fidus/fluid/rigid_mode_correction.h>
#include <fidus/fluid/stokes_operator.h>
#include <fidus/fluid/stokes_solver.h>
#include <fidus/fluid/velocity_multigrid.h>
#include <limits>

namespace Fidus
{
  template <int dim>
  typename StokesSolver<dim>::RigidityResidual
  StokesSolver<dim>::rigidity_residual(const SolidIndicator<dim> &solid) const
  {
    FEValues<dim>                        fe_values(fe,
                            quadrature,
                            update_gradients | update_quadrature_points |
                              update_JxW_values);
    const FEValuesExtractors::Vector     velocities(0);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    std::vector<unsigned int>            cands;
    // In the held solid, in shared cells, total, box volume; then, per
    // particle, the held solid's strain and volume.
    const unsigned int  n_particles = solid.n_particles();
    std::vector<double> sums(4 + 2 * n_particles, 0.);
    for (const auto &cell : cells)
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_symmetric_gradients(solution, eps);
          solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
          // Slivers are reported with the released solid.
          const bool shared_cell = shared[cell->active_cell_index()] ||
                                   sliver[cell->active_cell_index()];
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double e2 = (eps[q] * eps[q]) * fe_values.JxW(q);
              sums[2] += e2;
              sums[3] += fe_values.JxW(q);
              int          k = -1;
              const double phi =
                cands.empty() ?
                  0. :
                  solid.fraction(fe_values.quadrature_point(q), cands, k);
              if (phi == 0.)
                continue;
              sums[shared_cell ? 1 : 0] += phi * e2;
              if (!shared_cell)
                {
                  const unsigned int i = solid.owner(k);
                  sums[4 + 2 * i] += phi * e2;
                  sums[5 + 2 * i] += phi * fe_values.JxW(q);
                }
            }
        }
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    RigidityResidual r;
    if (!(sums[2] > 0))
      return r;
    r.held       = std::sqrt(sums[0] / sums[2]);
    r.released   = std::sqrt(sums[1] / sums[2]);
    r.shear_rate = std::sqrt(2. * sums[2] / sums[3]);
    // A particle whose solid is all released has no held part to measure.
    for (unsigned int i = 0; i < n_particles; ++i)
      if (sums[5 + 2 * i] > 0.)
        r.particle =
          std::max(r.particle,
                   std::sqrt(sums[4 + 2 * i] / sums[5 + 2 * i]) / r.shear_rate);
    return r;
  }



  template <int dim>
  void
  StokesSolver<dim>::record_residual(Statistics             &stats,
                                     const RigidityResidual &residual) const
  {
    stats.rigidity_residual =
      settings.rigidity_per_particle ? residual.particle : residual.held;
    stats.particle_rigidity_residual = residual.particle;
    stats.shared_residual            = residual.released;
  }



  template <int dim>
  double
  StokesSolver<dim>::rigid_velocity_change(
    const std::vector<RigidMotion> &previous,
    const std::vector<RigidMotion> &current,
    const SolidIndicator<dim>      &solid,
    const double                    shear_rate,
    const double                    forced_velocity)
  {
    if (!(shear_rate > 0.) && !(forced_velocity > 0.))
      return 0.;
    double change = 0.;
    for (unsigned int i = 0; i < current.size(); ++i)
      {
        double du2 = 0., dw2 = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          {
            du2 +=
              std::pow(current[i].velocity[d] - previous[i].velocity[d], 2);
            dw2 += std::pow(current[i].omega[d] - previous[i].omega[d], 2);
          }
        const double a       = solid.radius(i);
        const double u_scale = std::max(shear_rate * a, forced_velocity);
        change               = std::max(
          {change, std::sqrt(du2) / u_scale, std::sqrt(dw2) * a / u_scale});
      }
    return change;
  }



  template <int dim>
  unsigned int
  StokesSolver<dim>::solve_linear(Statistics &stats, const double tolerance)
  {
    const auto &Q = preconditioners->rigid_body_correction;
    if (multigrid_active)
      return solve_linear(
        stats,
        DeflatedVelocityPreconditioner<VelocityMultigrid<dim>>(
          *velocity_block,
          *preconditioners->multigrid,
          Q),
        tolerance);
    return solve_linear(
      stats,
      DeflatedVelocityPreconditioner<TrilinosWrappers::PreconditionAMG>(
        *velocity_block,
        preconditioners->amg,
        Q),
      tolerance);
  }



  template <int dim>
  template <class VelocityPreconditioner>
  unsigned int
  StokesSolver<dim>::solve_linear(Statistics                   &stats,
                                  const VelocityPreconditioner &velocity,
                                  const double                  tolerance)
  {
    const double rhs_norm = rhs.l2_norm();
    if (rhs_norm == 0.)
      {
        distributed_solution = 0;
        constraints.distribute(distributed_solution);
        solution = distributed_solution;
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
    distributed_solution = 0;

    unsigned int iterations = 0;
    bool         done       = false;
    SolverFGMRES<TrilinosWrappers::MPI::BlockVector>::AdditionalData data(
      settings.gmres_restart);
    if (settings.max_cheap_iterations > 0)
      {
        SolverControl control(settings.max_cheap_iterations,
                              target,
                              false,
                              false);
        const BlockSchurPreconditioner<VelocityPreconditioner> cheap(
          system_matrix,
          *velocity_block,
          preconditioner_matrix.block(1, 1),
          velocity,
          preconditioners->jacobi,
          false);
        try
          {
            SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(control,
                                                                    data);
            solver.solve(StokesOperator(system_matrix, *velocity_block),
                         distributed_solution,
                         rhs,
                         cheap);
            done = true;
          }
        catch (const SolverControl::NoConvergence &)
          {}
        iterations += control.last_step();
      }
    if (!done)
      {
        ++stats.expensive_solves;
        SolverControl control(settings.max_linear_iterations,
                              target,
                              false,
                              false);
        const BlockSchurPreconditioner<VelocityPreconditioner> expensive(
          system_matrix,
          *velocity_block,
          preconditioner_matrix.block(1, 1),
          velocity,
          preconditioners->jacobi,
          true);
        try
          {
            SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(control,
                                                                    data);
            solver.solve(StokesOperator(system_matrix, *velocity_block),
                         distributed_solution,
                         rhs,
                         expensive);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            std::ostringstream s;
            s << "the Stokes solver (FGMRES) did not converge in "
              << e.last_step << " iterations: residual " << e.last_residual
              << " > target " << target << " (Fluid/Linear solver/Tolerance = "
              << settings.linear_tolerance << ", this solve's tolerance "
              << tolerance
              << "); try more 'Maximum iterations' or a smaller 'Penalty "
                 "factor'";
            throw RunError(s.str());
          }
        iterations += control.last_step();
        stats.inner_iterations += expensive.inner_iterations;
      }
    constraints.distribute(distributed_solution);
    solution = distributed_solution;
    return iterations;
  }



  template <int dim>
  typename StokesSolver<dim>::Statistics
  StokesSolver<dim>::solve(const SolidIndicator<dim> &solid,
                           const Function<dim>       &boundary_velocity,
                           const Function<dim>       *body_force,
                           const Function<dim>       *fluid_viscosity)
  {
    Statistics stats;
    Timer      timer;

    // Boundary values change with the shear rate: rebuild the constraints
    // (same constrained set as in setup_dofs, new inhomogeneities).
    make_constraints(boundary_velocity);
    // Part of the assembly time, printed apart in verbose output: what
    // keeping the hanging-node and periodicity constraints per mesh (and
    // changing only the inhomogeneities) could save at most.
    const double constraint_seconds = timer.wall_time();

    assemble_system(solid, body_force, fluid_viscosity);
    stats.shared_cells     = n_shared_cells;
    stats.assemble_seconds = timer.wall_time();

    timer.restart();
    setup_preconditioners(solid, fluid_viscosity);
    if (!velocity_block_assembled())
      subtract_constraint_load();
    stats.setup_seconds = timer.wall_time();

    timer.restart();
    const double rho = 2. * (settings.penalty_factor - 1.) * settings.viscosity;
    if (!multiplier_valid || !settings.reuse_multiplier)
      {
        distributed_multiplier = 0;
        multiplier             = distributed_multiplier;
      }
    else
      {
        // The warm start lives on the solid of the previous step. Its
        // values on DoFs that are no longer in the solid mask (the particle
        // moved off them, or their cells are now shared) would never be
        // updated by the loop, which only changes masked DoFs, yet they
        // still load the held solid next to them through e(lambda): a
        // frozen error that stalled the loop every other step in a dense
        // suspension (doc/fluid.md). Keep only the masked part.
        distributed_multiplier.block(0).scale(solid_mask.block(0));
        multiplier = distributed_multiplier;
      }
    if (solid.n_particles() == 0)
      {
        assemble_multiplier_rhs(solid);
        stats.linear_iterations +=
          solve_linear(stats, settings.linear_tolerance);
        stats.uzawa_iterations  = 1;
        stats.rigidity_residual = 0.;
      }
    else
      {
        stats.uzawa_converged = false;
        // The Uzawa map  lambda -> lambda + rho M u(lambda)  (M: the solid
        // mask) is affine in lambda; each iteration is one linear solve.
        // Plain Uzawa contracts each mode by 1 / (1 + rho mu), where mu
        // measures how much of the mode's strain lies in the solid; modes
        // on thin solid slivers of cut cells contract slowly, and the
        // no-progress rule below ends such a loop (doc/fluid.md).
        // The masked velocity of the update, allocated once per solve.
        TrilinosWrappers::MPI::Vector update(distributed_multiplier.block(0));
        double previous_residual = std::numeric_limits<double>::max();
        // The particles' rigid velocities after each iteration: what the
        // time loop takes from the solve. With Rigid velocity tolerance the
        // loop stops on their change instead of on the strain left in the
        // solid, whose cut-cell sliver modes contract slowly but barely
        // move the particles (doc/fluid.md).
        const bool by_velocity = settings.rigid_velocity_tolerance > 0.;
        std::vector<RigidMotion> motions, previous_motions;
        stats.rigid_velocity_change = std::numeric_limits<double>::quiet_NaN();
        // Inexact Uzawa: a velocity inside the loop only has to be accurate
        // next to the loop's own tolerance, which is what it is compared
        // with. The velocity the loop ends on must meet the linear
        // tolerance, so the solve that is predicted to be the last (from
        // the loop's contraction so far) is exact, and if the loop ends on
        // an inexact one, that one is solved again. Not carried on from
        // the inexact velocity: FGMRES from it needed 2.5 times the
        // iterations of a solve from zero (doc/fluid.md).
        const double loop_tolerance =
          std::max(settings.linear_tolerance,
                   settings.inexact_uzawa_factor *
                     (by_velocity ? settings.rigid_velocity_tolerance :
                                    settings.rigidity_tolerance));
        // With Reuse multiplier the first solve is usually the last: from
        // the last step's multiplier, and also after a remesh, where the
        // penalty alone mostly meets the tolerance (the 2D paper scene:
        // one Uzawa iteration per step). Without it the loop starts from
        // zero every step and takes several (a dense suspension: 4-5).
        double next_tolerance = settings.reuse_multiplier ?
                                  settings.linear_tolerance :
                                  loop_tolerance;
        bool   last_exact     = false;
        // The passes over the solid that each iteration makes besides its
        // linear solve (multiplier load, rigidity residual, rigid
        // motions), timed apart: what a per-step table of the solid's
        // quadrature points could save at most.
        Timer passes;
        passes.stop();
        for (unsigned int k = 0; k < settings.max_uzawa_iterations; ++k)
          {
            passes.start();
            assemble_multiplier_rhs(solid);
            passes.stop();
            last_exact = next_tolerance <= settings.linear_tolerance;
            stats.linear_iterations += solve_linear(stats, next_tolerance);
            ++stats.uzawa_iterations;
            passes.start();
            const RigidityResidual residual = rigidity_residual(solid);
            record_residual(stats, residual);
            motions = compute_rigid_motions(dof_handler,
                                            cells,
                                            solution,
                                            solid,
                                            quadrature,
                                            &shared);
            passes.stop();
            if (k > 0)
              stats.rigid_velocity_change =
                rigid_velocity_change(previous_motions,
                                      motions,
                                      solid,
                                      residual.shear_rate,
                                      settings.forced_velocity_scale);
            std::swap(motions, previous_motions);
            if (settings.verbose &&
                Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
              std::cout << "    Uzawa " << k << ": rigidity residual "
                        << stats.rigidity_residual << ", rigid velocity change "
                        << stats.rigid_velocity_change << ", FGMRES total "
                        << stats.linear_iterations << ", expensive "
                        << stats.expensive_solves << std::endl;
            if (!std::isfinite(stats.rigidity_residual))
              throw RunError("the Uzawa loop produced a non-finite rigidity "
                             "residual (NaN or inf in the velocity)");
            // The measure the loop is stopped on.
            const double measure   = by_velocity ? stats.rigid_velocity_change :
                                                   stats.rigidity_residual;
            const double tolerance = by_velocity ?
                                       settings.rigid_velocity_tolerance :
                                       settings.rigidity_tolerance;
            // The velocity's change needs two iterations.
            const bool measured = !by_velocity || k > 0;
            if (measured && measure < tolerance)
              {
                stats.uzawa_converged = true;
                break;
              }
            // Stop a loop that no longer makes progress instead of spending
            // the remaining iterations (each a full linear solve) on it:
            // the measure grew (a particle touching a Dirichlet face,
            // where rigidity and the imposed velocity contradict each
            // other) or fell by less than 2 % in one iteration (the plateau
            // of cut-cell slivers). The penalised solution stands; the
            // caller reports the residual.
            if (measured &&
                previous_residual < std::numeric_limits<double>::max() &&
                measure > 0.98 * previous_residual)
              {
                stats.uzawa_stalled = true;
                break;
              }
            // Is the next iteration the last? The measure contracts about
            // geometrically; predict it from the last two values.
            const bool next_is_last =
              k + 2 >= settings.max_uzawa_iterations ||
              (measured &&
               previous_residual < std::numeric_limits<double>::max() &&
               measure * measure / previous_residual < tolerance);
            next_tolerance =
              next_is_last ? settings.linear_tolerance : loop_tolerance;
            if (measured)
              previous_residual = measure;
            // The last iteration keeps the multiplier its solution was
            // computed with: the stress (HydrodynamicStress) needs the
            // pair that satisfies the momentum equation.
            if (k + 1 == settings.max_uzawa_iterations)
              break;
            // lambda += rho M u: the plain Uzawa update, in place.
            {
              TrilinosWrappers::MPI::Vector &x =
                distributed_multiplier.block(0);
              update = distributed_solution.block(0);
              update.scale(solid_mask.block(0));
              x.add(rho, update);
            }
            multiplier = distributed_multiplier;
          }
        if (!last_exact)
          {
            // The right-hand side is still that of the last multiplier.
            stats.linear_iterations +=
              solve_linear(stats, settings.linear_tolerance);
            record_residual(stats, rigidity_residual(solid));
            if (!std::isfinite(stats.rigidity_residual))
              throw RunError("the Uzawa loop produced a non-finite rigidity "
                             "residual (NaN or inf in the velocity)");
            if (settings.verbose &&
                Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
              std::cout << "    Uzawa, last velocity again, exact: "
                        << "rigidity residual " << stats.rigidity_residual
                        << ", FGMRES total " << stats.linear_iterations
                        << std::endl;
          }
        stats.solid_pass_seconds = passes.wall_time();
        // Only the multiplier of a converged loop is a warm start for the
        // next solve. Where rigidity cannot be met (two particles closer
        // than a cell, so one cell would have to carry two rigid motions;
        // a particle touching a Dirichlet face), lambda grows with every
        // iteration; carried from step to step it kept growing and drove
        // the particle velocities to garbage within a few steps (dense
        // suspension, 100 discs at level 6: max |omega| 1.3 -> 25 -> 34,
        // doc/fluid.md).
        multiplier_valid = stats.uzawa_converged;
      }

    // Report a pressure of zero mean.
    const double mean =
      VectorTools::compute_mean_value(dof_handler, quadrature, solution, dim);
    distributed_solution.block(1).add(-mean);
    solution            = distributed_solution;
    stats.solve_seconds = timer.wall_time();
    if (settings.verbose &&
        Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::cout << "    Stokes: assembly " << stats.assemble_seconds
                << " s (of which constraints " << constraint_seconds
                << " s), preconditioner set-up " << stats.setup_seconds
                << " s, Uzawa/FGMRES " << stats.solve_seconds
                << " s (of which passes over the solid "
                << stats.solid_pass_seconds << " s), DoFs " << n_dofs()
                << std::endl;
    return stats;
  }

  // The class is instantiated in stokes_solver.cc; here only the members
  // defined in this file.
  template typename StokesSolver<2>::Statistics
  StokesSolver<2>::solve(const SolidIndicator<2> &,
                         const Function<2> &,
                         const Function<2> *,
                         const Function<2> *);
  template typename StokesSolver<3>::Statistics
  StokesSolver<3>::solve(const SolidIndicator<3> &,
                         const Function<3> &,
                         const Function<3> *,
                         const Function<3> *);
} // namespace Fidus
