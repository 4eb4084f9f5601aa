#ifndef fidus_tests_stress_tools_h
#define fidus_tests_stress_tools_h

// Scene builders shared by the stress tests: random non-overlapping
// particle layouts written as a 'Particles/Positions' value.

#include <array>
#include <cmath>
#include <cstdint>
#include <fidus/simulation/simulation.h>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace FidusTest
{
  /**
   * Random sequential addition of @p n equal spheres (discs in 2D) of radius
   * @p a in the unit box, at least @p clearance apart and from the y walls.
   * Directions other than y are periodic (the 'sliding walls' box), so the
   * distance uses the minimum image there. The generator is seeded, and
   * uses only the raw 32-bit output of mt19937, so the layout is the same on
   * every platform.
   */
  inline std::vector<std::array<double, 3>>
  random_layout(const unsigned int dim,
                const unsigned int n,
                const double       a,
                const double       clearance,
                const unsigned int seed)
  {
    std::mt19937 rng(seed);
    auto         uniform = [&]() { return rng() / 4294967296.; };
    std::vector<std::array<double, 3>> x;
    for (unsigned int attempt = 0; x.size() < n && attempt < 10000000;
         ++attempt)
      {
        std::array<double, 3> p = {{0, 0, 0}};
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = uniform();
        if (p[1] < a + clearance || p[1] > 1 - a - clearance)
          continue;
        bool ok = true;
        for (const auto &q : x)
          {
            double r2 = 0;
            for (unsigned int d = 0; d < dim; ++d)
              {
                double dx = p[d] - q[d];
                if (d != 1)
                  dx -= std::round(dx);
                r2 += dx * dx;
              }
            if (r2 < std::pow(2 * a + clearance, 2))
              {
                ok = false;
                break;
              }
          }
        if (ok)
          x.push_back(p);
      }
    return x;
  }

  /// True if no position, velocity or angular velocity of the final state
  /// is NaN or infinite.
  inline bool
  finite_state(const Fidus::RunSummary &s)
  {
    for (const auto &v : {s.positions, s.velocities, s.omegas})
      for (const auto &p : v)
        for (const double c : p)
          if (!std::isfinite(c))
            return false;
    return true;
  }

  /// 'x, y[, z]; ...' with 17 digits.
  inline std::string
  positions_entry(const std::vector<std::array<double, 3>> &x,
                  const unsigned int                        dim)
  {
    std::ostringstream s;
    s.precision(17);
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        if (i > 0)
          s << "; ";
        for (unsigned int d = 0; d < dim; ++d)
          s << (d > 0 ? ", " : "") << x[i][d];
      }
    return s.str();
  }
} // namespace FidusTest

#endif
