#ifndef fidus_fluid_uzawa_loop_h
#define fidus_fluid_uzawa_loop_h

#include <fidus/fluid/fictitious_domain/rigid_motion.h>
#include <fidus/fluid/fictitious_domain/uzawa_problem.h>
#include <limits>
#include <vector>

namespace Fidus
{
  /**
   * The Uzawa loop of the augmented Lagrangian for rigidity: solve, measure,
   * update the multiplier, until the measure meets its tolerance, stops
   * falling, or the iterations run out.
   *
   * The map lambda -> lambda + rho M u(lambda) is affine in lambda, and each
   * iteration is one linear solve. Plain Uzawa contracts each mode by
   * 1 / (1 + rho mu), where mu measures how much of the mode's strain lies
   * in the solid; modes on thin solid slivers of cut cells contract slowly,
   * so the loop also stops when it makes no progress (doc/uzawa.md).
   *
   * The measure is the rigidity residual (box or per particle), or, with a
   * rigid velocity tolerance, the largest change of a particle's rigid
   * velocity in one iteration. With an inexact factor the solves inside the
   * loop stop early, and only the one predicted to be the last is solved to
   * the linear tolerance.
   */
  class UzawaLoop
  {
  public:
    /// The loop's settings (Parameters: Fluid and Fluid/Linear solver).
    struct Settings
    {
      double rigidity_tolerance = 1e-3;
      /// Compare rigidity_tolerance with Residual::particle instead of
      /// Residual::held.
      bool rigidity_per_particle = false;
      /// Stop on the rigid velocities' change instead (0: off).
      double rigid_velocity_tolerance = 0.;
      /// A velocity scale of the particles' forced motion (0: none); the
      /// change is measured against the larger of it and the shear.
      double       forced_velocity_scale = 0.;
      unsigned int max_iterations        = 50;
      double       linear_tolerance      = 1e-6;
      /// Solves inside the loop stop at this factor times the loop's
      /// tolerance (never below linear_tolerance; 0: all exact).
      double inexact_factor = 0.;
      /// Solve the first iteration to the linear tolerance (true when the
      /// multiplier is reused: the first solve is then usually the last).
      bool first_solve_exact = true;
      /// Print one line per iteration.
      bool print = false;
    };

    /// What one run() did.
    struct Result
    {
      unsigned int iterations = 0;
      /// Krylov iterations, summed over the solves.
      unsigned int linear_iterations = 0;
      /// The measure the loop stops on when it stops on strain
      /// (Residual::held or Residual::particle), of the last velocity.
      double rigidity_residual = 0.;
      /// Residual::particle and Residual::released of the last velocity.
      double particle_rigidity_residual = 0.;
      double released_residual          = 0.;
      /// Largest change of a particle's rigid velocity in the last
      /// iteration (rigid_velocity_change()); NaN after a single
      /// iteration.
      double rigid_velocity_change = std::numeric_limits<double>::quiet_NaN();
      bool   converged             = false;
      /// The loop stopped early: no progress.
      bool stalled = false;
      /// Time spent in the problem's passes over the solid (multiplier
      /// load, residual, rigid motions), besides the linear solves.
      double solid_pass_seconds = 0.;
    };

    /// A loop with @p settings.
    explicit UzawaLoop(const Settings &settings);

    /// Iterate on @p problem from its current multiplier. On return the
    /// problem's velocity is the solution for the multiplier it holds, to
    /// the linear tolerance. Throws RunError on a non-finite residual.
    Result
    run(UzawaProblem &problem) const;

    /// Largest change of a particle's rigid velocity between @p previous
    /// and @p current: |dU| / s and a |d omega| / s, with s the larger of
    /// @p shear_rate times the radius a and @p forced_velocity. Zero when
    /// both scales vanish.
    static double
    rigid_velocity_change(const std::vector<RigidMotion> &previous,
                          const std::vector<RigidMotion> &current,
                          const UzawaProblem             &problem,
                          double                          shear_rate,
                          double                          forced_velocity);

  private:
    /// Write @p residual into @p result.
    void
    record(Result &result, const UzawaProblem::Residual &residual) const;

    const Settings settings;
  };
} // namespace Fidus

#endif
