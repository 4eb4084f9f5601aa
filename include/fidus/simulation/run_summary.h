#ifndef fidus_simulation_run_summary_h
#define fidus_simulation_run_summary_h

#include <array>
#include <fidus/rheology/suspension_stress.h>
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
    /// Largest number of shared cells of a solve (their solid released)
    /// and the largest rigidity residual in them.
    unsigned int max_shared_cells    = 0;
    double       max_shared_residual = 0.;
    /// Largest StokesSolver::multigrid_galerkin_defect() of the run.
    double multigrid_galerkin_defect = 0.;
    /// Cells and DoFs of the last solve.
    unsigned long long n_cells = 0, n_dofs = 0;
    /// The smallest GMRES restart a solve used ('Fluid/Linear
    /// solver/GMRES restart', or less where its basis did not fit in
    /// memory); 0 when no solve was iterative.
    unsigned int smallest_gmres_restart = 0;
    /// Errors of the 'exact rigid inclusion' scene (else 0): L2 and H1 of u
    /// on the fluid part, |omega + g/2| / (g/2) and |U| / (g a).
    double u_l2_error = 0., u_h1_error = 0., omega_error = 0.,
           translation_error = 0.;
    /// L2 norm of the exact velocity on the same region (same scene).
    double u_l2_norm = 0.;
    /// Wall seconds of the whole run (earlier parts of a resumed run
    /// included).
    double wall_seconds = 0.;
    /// The largest resident memory of any rank during the run, in bytes
    /// (0 where the operating system does not report it).
    double peak_memory_per_rank = 0.;
    /// The signal that stopped the run before its End time (0: none).
    int stop_signal = 0;
    /// Stress of the last step: the statistics.csv columns, the
    /// hydrodynamic stress of the box by volume average and at the walls
    /// (3 x 3, row-major; NaN where a wall direction is missing), the box's
    /// mean strain rate, its solid fraction and every particle's stresslet
    /// (xx, xy, xz, yy, yz, zz).
    SuspensionStress                   stress;
    std::array<double, 9>              hydrodynamic_stress{}, wall_stress{};
    std::array<double, 9>              mean_strain_rate{};
    double                             solid_fraction = 0.;
    std::vector<std::array<double, 6>> stresslets;
  };
} // namespace Fidus

#endif
