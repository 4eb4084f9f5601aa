#ifndef fidus_simulation_simulation_h
#define fidus_simulation_simulation_h

#include <array>
#include <fidus/core/parameters.h>

namespace dealii
{
  class TimerOutput;
}
#include <string>
#include <vector>

namespace Fidus
{
  /// Summary of a run, for tests and benchmarks.
  struct RunSummary
  {
    unsigned int n_steps    = 0;
    double       final_time = 0.;
    /// State after the last step.
    std::vector<std::array<double, 3>> positions, velocities, omegas;
    /// Smallest gap between particles over the whole run (pairs only).
    double min_gap = 0.;
    /// Smallest normalised distance of particles 0 and 1 over the run.
    double min_normalised_distance = 0.;
    /// Largest Uzawa and linear iteration counts of any step.
    unsigned int max_uzawa_iterations = 0, max_linear_iterations = 0;
    /// Largest rigidity residual of any step.
    double max_rigidity_residual = 0.;
    /// Steps whose Uzawa loop or contact projection did not reach its
    /// tolerance (each was reported as a warning), and the largest number
    /// of dual-solver iterations of any projection.
    unsigned int uzawa_failures = 0, contact_failures = 0,
                 max_contact_iterations = 0;
    /// Cells and DoFs of the last solve.
    unsigned long long n_cells = 0, n_dofs = 0;
    /// Errors of the 'exact rigid inclusion' scene (else 0): L2 and H1 of u
    /// on the fluid part, |omega + g/2| / (g/2) and |U| / (g a).
    double u_l2_error = 0., u_h1_error = 0., omega_error = 0.,
           translation_error = 0.;
    /// L2 norm of the exact velocity on the fluid part (same scene).
    double u_l2_norm = 0.;
    /// Wall seconds of the whole run.
    double wall_seconds = 0.;
  };

  /**
   * The time loop of fidus (numerics sections 5 and 6) for one scene. The
   * only place that knows the order of the stages:
   *   mesh (refine around particles, skipped while they moved little)
   *   -> fluid (penalised Stokes, Uzawa) -> particles (rigid velocities)
   *   -> AB2 extrapolation -> contact (projection onto K, glue)
   *   -> displacement -> output.
   * The fluid and contact modules never see each other.
   */
  template <int dim>
  class Simulation
  {
  public:
    /// @p parameters must have passed Parameters::parse().
    explicit Simulation(const Parameters &parameters);

    /// Run the scene; output goes to the output directory.
    RunSummary
    run();

  private:
    /// The time loop proper; @p timer collects the stage timings.
    RunSummary
    run_steps(dealii::TimerOutput &timer);

    const Parameters &prm;
  };

  /// Run a scene in its dimension (picks Simulation<2> or <3>).
  RunSummary
  run_simulation(const Parameters &parameters);
} // namespace Fidus

#endif
