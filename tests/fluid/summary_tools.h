// Helpers shared by the fluid tests that compare two runs' summaries.
#ifndef fidus_tests_fluid_summary_tools_h
#define fidus_tests_fluid_summary_tools_h

#include <algorithm>
#include <cmath>
#include <fidus/simulation/simulation.h>

namespace FidusTest
{
  /// Largest difference of the particles' velocities (over @p radius) and
  /// rotations between two runs of the same scene.
  inline double
  difference(const Fidus::RunSummary &a,
             const Fidus::RunSummary &b,
             const double             radius)
  {
    double d = 0.;
    for (unsigned int p = 0; p < a.velocities.size(); ++p)
      for (unsigned int c = 0; c < 3; ++c)
        d =
          std::max({d,
                    std::abs(a.velocities[p][c] - b.velocities[p][c]) / radius,
                    std::abs(a.omegas[p][c] - b.omegas[p][c])});
    return d;
  }

  /// FGMRES iterations per Uzawa solve of a run's worst step.
  inline double
  per_solve(const Fidus::RunSummary &s)
  {
    return double(s.max_linear_iterations) / s.max_uzawa_iterations;
  }
} // namespace FidusTest

#endif
