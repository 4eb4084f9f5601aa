// StokesSolver::solve(): the solver as the problem of the Uzawa loop
// (UzawaLoop, augmented Lagrangian for rigidity), the strain left in the
// solid, and the FGMRES solve of each iteration; the rest of the class
// (DoFs, constraints, assembly, errors) is in stokes_solver.cc.
#include "stokes_linear_solvers.h"

#include <cmath>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <deque>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/anderson_mixing.h>
#include <fidus/fluid/fictitious_domain/block_schur_preconditioner.h>
#include <fidus/fluid/fictitious_domain/deflated_velocity_preconditioner.h>
#include <fidus/fluid/fictitious_domain/rigid_mode_correction.h>
#include <fidus/fluid/fictitious_domain/stokes_operator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/fluid/fictitious_domain/velocity_multigrid.h>
#include <limits>

namespace Fidus
{
  template <int dim>
  UzawaProblem::Residual
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
    UzawaProblem::Residual r;
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
  std::vector<double>
  StokesSolver<dim>::held_strain_products(
    const SolidIndicator<dim>                                     &solid,
    const TrilinosWrappers::MPI::BlockVector                      &v,
    const std::vector<const TrilinosWrappers::MPI::BlockVector *> &w) const
  {
    FEValues<dim>                                     fe_values(fe,
                            quadrature,
                            update_gradients | update_quadrature_points |
                              update_JxW_values);
    const FEValuesExtractors::Vector                  velocities(0);
    std::vector<SymmetricTensor<2, dim>>              eps_v(quadrature.size());
    std::vector<std::vector<SymmetricTensor<2, dim>>> eps_w(
      w.size(),
      std::vector<SymmetricTensor<2, dim>>(quadrature.size()));
    std::vector<double>       weight(quadrature.size());
    std::vector<unsigned int> cands;
    std::vector<double>       sums(w.size() + 1, 0.);
    for (const auto &cell : cells)
      if (cell->is_locally_owned() && !shared[cell->active_cell_index()] &&
          !sliver[cell->active_cell_index()])
        {
          solid.candidates(cell->center(), 0.5 * cell->diameter(), cands);
          if (cands.empty())
            continue;
          fe_values.reinit(cell);
          bool any = false;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              int k = -1;
              weight[q] =
                solid.fraction(fe_values.quadrature_point(q), cands, k) *
                fe_values.JxW(q);
              any = any || weight[q] != 0.;
            }
          if (!any)
            continue;
          fe_values[velocities].get_function_symmetric_gradients(v, eps_v);
          for (unsigned int i = 0; i < w.size(); ++i)
            fe_values[velocities].get_function_symmetric_gradients(*w[i],
                                                                   eps_w[i]);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            if (weight[q] != 0.)
              {
                for (unsigned int i = 0; i < w.size(); ++i)
                  sums[i] += weight[q] * (eps_v[q] * eps_w[i][q]);
                sums.back() += weight[q] * (eps_v[q] * eps_v[q]);
              }
        }
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    return sums;
  }



  /**
   * StokesSolver as the problem of the Uzawa loop: the multiplier's load,
   * one FGMRES solve, the strain left in the solid, the rigid motions and
   * the plain Uzawa update, on the solver's own vectors.
   */
  template <int dim>
  class StokesSolver<dim>::Uzawa : public UzawaProblem
  {
  public:
    Uzawa(StokesSolver<dim>         &solver,
          const SolidIndicator<dim> &solid,
          Statistics                &stats)
      : solver(solver)
      , solid(solid)
      , stats(stats)
      , update(solver.distributed_multiplier.block(0))
      , rho(2. * (solver.settings.penalty_factor - 1.) *
            solver.settings.viscosity)
      , mixing(solver.settings.uzawa_acceleration_depth)
    {}

    void
    load_multiplier() override
    {
      solver.assemble_multiplier_rhs(solid);
    }

    unsigned int
    solve_velocity(const double tolerance) override
    {
      return solver.solve_linear(stats, tolerance);
    }

    Residual
    rigidity_residual() const override
    {
      return solver.rigidity_residual(solid);
    }

    std::vector<RigidMotion>
    rigid_motions() const override
    {
      return compute_rigid_motions(solver.dof_handler,
                                   solver.cells,
                                   solver.solution,
                                   solid,
                                   solver.quadrature,
                                   &solver.shared);
    }

    double
    particle_radius(const unsigned int i) const override
    {
      return solid.radius(i);
    }

    void
    update_multiplier() override
    {
      TrilinosWrappers::MPI::Vector &x = solver.distributed_multiplier.block(0);
      if (mixing.depth() == 0)
        {
          // lambda += rho M u, in place, on the held solid's DoFs only.
          update = solver.distributed_solution.block(0);
          update.scale(solver.solid_mask.block(0));
          x.add(rho, update);
        }
      else
        accelerated_update(x);
      solver.multiplier = solver.distributed_multiplier;
    }

  private:
    /**
     * Anderson's update: with u_i = u(lambda_i) the last iterates' velocities
     * and alpha the weights (sum 1) that make the strain of sum alpha_i u_i
     * in the held solid least, lambda = sum alpha_i (lambda_i + rho M u_i).
     * The map lambda -> u(lambda) is affine, so sum alpha_i u_i is the
     * velocity of sum alpha_i lambda_i, and the update is the plain one
     * from that better multiplier. The strain is measured in the inner
     * product of Residual::held, which ignores the rigid motions that
     * lambda accumulates (they load nothing).
     */
    void
    accelerated_update(TrilinosWrappers::MPI::Vector &x)
    {
      if (mixing.size() == mixing.depth() + 1)
        {
          mixing.drop_oldest();
          multipliers.pop_front();
          velocities.pop_front();
        }
      std::vector<const TrilinosWrappers::MPI::BlockVector *> earlier;
      for (const auto &u : velocities)
        earlier.push_back(&u);
      mixing.push(solver.held_strain_products(solid, solver.solution, earlier));
      multipliers.push_back(x);
      velocities.push_back(solver.solution);

      const std::vector<double> alpha = mixing.weights();
      x                               = 0.;
      update                          = 0.;
      for (unsigned int i = 0; i < alpha.size(); ++i)
        {
          x.add(alpha[i], multipliers[i]);
          // From the ghosted copy into the owned layout (an import). The
          // vector is allocated here, not with the problem, so that the
          // plain update holds no more memory than it did.
          if (owned_velocity.size() == 0)
            owned_velocity.reinit(update);
          owned_velocity = velocities[i].block(0);
          update.add(alpha[i], owned_velocity);
        }
      update.scale(solver.solid_mask.block(0));
      x.add(rho, update);
    }

    StokesSolver<dim>         &solver;
    const SolidIndicator<dim> &solid;
    Statistics                &stats;
    /// The masked velocity of the update, allocated once per solve.
    TrilinosWrappers::MPI::Vector update;
    const double                  rho;
    /// Anderson acceleration (Settings::uzawa_acceleration_depth > 0): the
    /// weights, and the iterates they combine, oldest first.
    AndersonMixing                                 mixing;
    std::deque<TrilinosWrappers::MPI::Vector>      multipliers;
    std::deque<TrilinosWrappers::MPI::BlockVector> velocities;
    TrilinosWrappers::MPI::Vector                  owned_velocity;
  };



  template <int dim>
  unsigned int
  StokesSolver<dim>::solve_linear(Statistics &stats, const double tolerance)
  {
    return linear_solver->solve(stats, tolerance);
  }



  template <int dim>
  typename StokesSolver<dim>::Statistics
  StokesSolver<dim>::solve(const SolidIndicator<dim> &solid,
                           const Function<dim>       &boundary_velocity,
                           const Function<dim>       *body_force,
                           const Function<dim>       *fluid_viscosity,
                           const double               linear_tolerance)
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
    linear_solver->setup(solid, fluid_viscosity);
    stats.setup_seconds = timer.wall_time();

    if (keep_rhs_for_resolve)
      saved_base_rhs = base_rhs;
    run_uzawa_loop(solid, !settings.reuse_multiplier, stats, linear_tolerance);
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


  template <int dim>
  typename StokesSolver<dim>::Statistics
  StokesSolver<dim>::resolve(const SolidIndicator<dim> &solid,
                             const Function<dim>       &extra_force,
                             const double               linear_tolerance)
  {
    Assert(keep_rhs_for_resolve && saved_base_rhs.size() == base_rhs.size(),
           ExcMessage("resolve() needs keep_right_hand_side() before the "
                      "solve() it repeats"));
    Statistics stats;
    Timer      timer;
    base_rhs = saved_base_rhs;
    add_body_force_rhs(solid, extra_force);
    stats.assemble_seconds = timer.wall_time();
    stats.shared_cells     = n_shared_cells;
    // The same solid: the last multiplier is a warm start even where
    // Reuse multiplier is off (that guards against a moved solid).
    run_uzawa_loop(solid, false, stats, linear_tolerance);
    if (settings.verbose &&
        Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::cout << "    Stokes again with new loads: right-hand side "
                << stats.assemble_seconds << " s, Uzawa/FGMRES "
                << stats.solve_seconds << " s" << std::endl;
    return stats;
  }



  template <int dim>
  void
  StokesSolver<dim>::run_uzawa_loop(const SolidIndicator<dim> &solid,
                                    const bool                 start_from_zero,
                                    Statistics                &stats,
                                    const double               linear_tolerance)
  {
    const double tolerance =
      std::max(settings.linear_tolerance, linear_tolerance);
    Timer      timer;
    const bool warm = multiplier_valid && !start_from_zero;
    if (!warm)
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
        // suspension (doc/uzawa.md). Keep only the masked part.
        distributed_multiplier.block(0).scale(solid_mask.block(0));
        multiplier = distributed_multiplier;
      }
    if (solid.n_particles() == 0)
      {
        assemble_multiplier_rhs(solid);
        stats.linear_iterations += solve_linear(stats, tolerance);
        stats.uzawa_iterations  = 1;
        stats.rigidity_residual = 0.;
      }
    else
      {
        UzawaLoop::Settings loop_settings;
        loop_settings.rigidity_tolerance    = settings.rigidity_tolerance;
        loop_settings.rigidity_per_particle = settings.rigidity_per_particle;
        loop_settings.rigid_velocity_tolerance =
          settings.rigid_velocity_tolerance;
        loop_settings.forced_velocity_scale = settings.forced_velocity_scale;
        loop_settings.max_iterations        = settings.max_uzawa_iterations;
        loop_settings.linear_tolerance      = tolerance;
        loop_settings.inexact_factor        = settings.inexact_uzawa_factor;
        // With Reuse multiplier the first solve is usually the last: from
        // the last step's multiplier, and also after a remesh, where the
        // penalty alone mostly meets the tolerance (the 2D paper scene:
        // one Uzawa iteration per step). Without it the loop starts from
        // zero every step and takes several (a dense suspension: 4-5).
        // A solve with new loads only (resolve()) starts from the
        // multiplier of the same solid, and its first solve is usually its
        // last too (the dense 3D scene: one Uzawa iteration in most).
        loop_settings.first_solve_exact = settings.reuse_multiplier || warm;
        loop_settings.print =
          settings.verbose &&
          Utilities::MPI::this_mpi_process(mpi_communicator) == 0;

        Uzawa                   problem(*this, solid, stats);
        const UzawaLoop::Result loop = UzawaLoop(loop_settings).run(problem);
        stats.uzawa_iterations       = loop.iterations;
        stats.linear_iterations += loop.linear_iterations;
        stats.rigidity_residual          = loop.rigidity_residual;
        stats.particle_rigidity_residual = loop.particle_rigidity_residual;
        stats.shared_residual            = loop.released_residual;
        stats.rigid_velocity_change      = loop.rigid_velocity_change;
        stats.uzawa_converged            = loop.converged;
        stats.uzawa_stalled              = loop.stalled;
        stats.solid_pass_seconds         = loop.solid_pass_seconds;
        // Only the multiplier of a converged loop is a warm start for the
        // next solve. Where rigidity cannot be met (two particles closer
        // than a cell, so one cell would have to carry two rigid motions;
        // a particle touching a Dirichlet face), lambda grows with every
        // iteration; carried from step to step it kept growing and drove
        // the particle velocities to garbage within a few steps (dense
        // suspension, 100 discs at level 6: max |omega| 1.3 -> 25 -> 34,
        // doc/uzawa.md).
        multiplier_valid = stats.uzawa_converged;
      }

    // Report a pressure of zero mean.
    const double mean =
      VectorTools::compute_mean_value(dof_handler, quadrature, solution, dim);
    distributed_solution.block(1).add(-mean);
    solution            = distributed_solution;
    stats.solve_seconds = timer.wall_time();
  }

  // The class is instantiated in stokes_solver.cc; here only the members
  // defined in this file.
  template typename StokesSolver<2>::Statistics
  StokesSolver<2>::solve(const SolidIndicator<2> &,
                         const Function<2> &,
                         const Function<2> *,
                         const Function<2> *,
                         double);
  template typename StokesSolver<3>::Statistics
  StokesSolver<3>::solve(const SolidIndicator<3> &,
                         const Function<3> &,
                         const Function<3> *,
                         const Function<3> *,
                         double);
  template typename StokesSolver<2>::Statistics
  StokesSolver<2>::resolve(const SolidIndicator<2> &,
                           const Function<2> &,
                           double);
  template typename StokesSolver<3>::Statistics
  StokesSolver<3>::resolve(const SolidIndicator<3> &,
                           const Function<3> &,
                           double);
  template void
  StokesSolver<2>::run_uzawa_loop(const SolidIndicator<2> &,
                                  bool,
                                  StokesSolver<2>::Statistics &,
                                  double);
  template void
  StokesSolver<3>::run_uzawa_loop(const SolidIndicator<3> &,
                                  bool,
                                  StokesSolver<3>::Statistics &,
                                  double);
} // namespace Fidus
