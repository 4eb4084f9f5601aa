#include <algorithm>
#include <cmath>
#include <deal.II/base/timer.h>
#include <fidus/core/input_error.h>
#include <fidus/fluid/fictitious_domain/uzawa_loop.h>
#include <iostream>

namespace Fidus
{
  UzawaLoop::UzawaLoop(const Settings &settings)
    : settings(settings)
  {}



  double
  UzawaLoop::rigid_velocity_change(const std::vector<RigidMotion> &previous,
                                   const std::vector<RigidMotion> &current,
                                   const UzawaProblem             &problem,
                                   const double                    shear_rate,
                                   const double forced_velocity)
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
        const double a       = problem.particle_radius(i);
        const double u_scale = std::max(shear_rate * a, forced_velocity);
        change               = std::max(
          {change, std::sqrt(du2) / u_scale, std::sqrt(dw2) * a / u_scale});
      }
    return change;
  }



  void
  UzawaLoop::record(Result                       &result,
                    const UzawaProblem::Residual &residual) const
  {
    result.rigidity_residual =
      settings.rigidity_per_particle ? residual.particle : residual.held;
    result.particle_rigidity_residual = residual.particle;
    result.released_residual          = residual.released;
    if (!std::isfinite(result.rigidity_residual))
      throw RunError("the Uzawa loop produced a non-finite rigidity "
                     "residual (NaN or inf in the velocity)");
  }



  UzawaLoop::Result
  UzawaLoop::run(UzawaProblem &problem) const
  {
    Result result;
    // The passes over the solid that each iteration makes besides its
    // linear solve (multiplier load, rigidity residual, rigid motions),
    // timed apart: what a per-step table of the solid's quadrature points
    // could save at most.
    dealii::Timer passes;
    passes.stop();

    // The particles' rigid velocities after each iteration: what the time
    // loop takes from the solve. With a rigid velocity tolerance the loop
    // stops on their change instead of on the strain left in the solid,
    // whose cut-cell sliver modes contract slowly but barely move the
    // particles (doc/uzawa.md).
    const bool   by_velocity = settings.rigid_velocity_tolerance > 0.;
    const double tolerance   = by_velocity ? settings.rigid_velocity_tolerance :
                                             settings.rigidity_tolerance;
    std::vector<RigidMotion> motions, previous_motions;

    // Inexact Uzawa: a velocity inside the loop only has to be accurate
    // next to the loop's own tolerance, which is what it is compared with.
    // The velocity the loop ends on must meet the linear tolerance, so the
    // solve that is predicted to be the last (from the loop's contraction
    // so far) is exact, and if the loop ends on an inexact one, that one is
    // solved again. Not carried on from the inexact velocity: FGMRES from
    // it needed 2.5 times the iterations of a solve from zero
    // (doc/uzawa.md).
    const double loop_tolerance =
      std::max(settings.linear_tolerance, settings.inexact_factor * tolerance);
    double next_tolerance =
      settings.first_solve_exact ? settings.linear_tolerance : loop_tolerance;
    bool   last_exact       = false;
    double previous_measure = std::numeric_limits<double>::max();
    bool   have_previous    = false;

    for (unsigned int k = 0; k < settings.max_iterations; ++k)
      {
        passes.start();
        problem.load_multiplier();
        passes.stop();
        last_exact = next_tolerance <= settings.linear_tolerance;
        result.linear_iterations += problem.solve_velocity(next_tolerance);
        ++result.iterations;
        passes.start();
        const UzawaProblem::Residual residual = problem.rigidity_residual();
        motions                               = problem.rigid_motions();
        passes.stop();
        if (k > 0)
          result.rigid_velocity_change =
            rigid_velocity_change(previous_motions,
                                  motions,
                                  problem,
                                  residual.shear_rate,
                                  settings.forced_velocity_scale);
        std::swap(motions, previous_motions);
        if (settings.print)
          std::cout << "    Uzawa " << k << ": rigidity residual "
                    << (settings.rigidity_per_particle ? residual.particle :
                                                         residual.held)
                    << ", rigid velocity change "
                    << result.rigid_velocity_change << ", FGMRES total "
                    << result.linear_iterations << std::endl;
        record(result, residual);

        const double measure =
          by_velocity ? result.rigid_velocity_change : result.rigidity_residual;
        // The velocity's change needs two iterations.
        const bool measured = !by_velocity || k > 0;
        if (measured && measure < tolerance)
          {
            result.converged = true;
            break;
          }
        // Stop a loop that no longer makes progress instead of spending the
        // remaining iterations (each a full linear solve) on it: the
        // measure grew (a particle touching a Dirichlet face, where
        // rigidity and the imposed velocity contradict each other) or fell
        // by less than 2 % in one iteration (the plateau of cut-cell
        // slivers). The penalised solution stands; the caller reports the
        // residual.
        if (measured && have_previous && measure > 0.98 * previous_measure)
          {
            result.stalled = true;
            break;
          }
        // Is the next iteration the last? The measure contracts about
        // geometrically; predict it from the last two values.
        const bool next_is_last =
          k + 2 >= settings.max_iterations ||
          (measured && have_previous &&
           measure * measure / previous_measure < tolerance);
        next_tolerance =
          next_is_last ? settings.linear_tolerance : loop_tolerance;
        if (measured)
          {
            previous_measure = measure;
            have_previous    = true;
          }
        // The last iteration keeps the multiplier its solution was computed
        // with: the stress (HydrodynamicStress) needs the pair that
        // satisfies the momentum equation.
        if (k + 1 == settings.max_iterations)
          break;
        problem.update_multiplier();
      }

    if (!last_exact)
      {
        // The right-hand side is still that of the last multiplier.
        result.linear_iterations +=
          problem.solve_velocity(settings.linear_tolerance);
        record(result, problem.rigidity_residual());
        if (settings.print)
          std::cout << "    Uzawa, last velocity again, exact: "
                    << "rigidity residual " << result.rigidity_residual
                    << ", FGMRES total " << result.linear_iterations
                    << std::endl;
      }
    result.solid_pass_seconds = passes.wall_time();
    return result;
  }
} // namespace Fidus
