#include <algorithm>
#include <array>
#include <cmath>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/lubrication/step_mean_resistance.h>
#include <limits>

namespace Fidus::Contact
{
  StepMeanResistance::StepMeanResistance(
    const std::vector<LubricationBond> &bonds,
    const unsigned int                  dimension,
    const double                        viscosity,
    const double                        roughness,
    const bool                          closing_only)
    : dimension(dimension)
    , viscosity(viscosity)
    , closing_only(closing_only)
  {
    const std::size_t m = bonds.size();
    h_try.resize(m);
    rough.resize(m);
    lo.assign(m, -std::numeric_limits<double>::infinity());
    hi.assign(m, std::numeric_limits<double>::infinity());
    g_lo.assign(m, 0.);
    g_hi.assign(m, 0.);
    for (std::size_t k = 0; k < m; ++k)
      {
        const LubricationBond &b    = bonds[k];
        const bool             wall = b.j == LubricationBond::no_particle;
        rough[k] = roughness * (wall ? b.a_i : std::min(b.a_i, b.a_j));
        h_try[k] = b.gap;
      }
  }



  double
  StepMeanResistance::next_resistance(const std::size_t      k,
                                      const LubricationBond &b,
                                      const double           reached)
  {
    const double g = reached - h_try[k];
    if (g >= 0. && h_try[k] > lo[k])
      lo[k] = h_try[k], g_lo[k] = g;
    if (g <= 0. && h_try[k] < hi[k])
      hi[k] = h_try[k], g_hi[k] = g;
    double next = reached;
    if (std::isfinite(lo[k]) && std::isfinite(hi[k]) && hi[k] > lo[k])
      next = g_lo[k] - g_hi[k] > 0. ?
               lo[k] + g_lo[k] * (hi[k] - lo[k]) / (g_lo[k] - g_hi[k]) :
               0.5 * (lo[k] + hi[k]);
    largest_change =
      std::max(largest_change,
               std::abs(next - h_try[k]) / std::max(std::abs(b.gap), rough[k]));
    h_try[k] = next;
    // An opening bond under closing_only keeps the start's resistance.
    const double end = closing_only ? std::min(next, b.gap) : next;
    return mean(b, dimension, viscosity, rough[k], b.gap, end);
  }



  double
  StepMeanResistance::take_largest_change()
  {
    const double c = largest_change;
    largest_change = 0.;
    return c;
  }



  double
  StepMeanResistance::mean(const LubricationBond &b,
                           const unsigned int     dimension,
                           const double           viscosity,
                           const double           roughness_gap,
                           const double           h0,
                           const double           h1)
  {
    // Without roughness the resistance of a closed gap is infinite: a
    // floor far below any gap a step can reach keeps the mean finite.
    const double floor      = std::max(roughness_gap, 1e-9 * b.a_i);
    const auto   resistance = [&](const double h) {
      return LubricationCorrection::squeeze_resistance(dimension,
                                                       viscosity,
                                                       b.a_i,
                                                       b.a_j,
                                                       std::max(h, floor));
    };
    const double lo = std::min(h0, h1), hi = std::max(h0, h1);
    if (hi - lo <= 1e-9 * std::max(hi, floor))
      return resistance(h0);
    // Below the floor the resistance is constant; above it R h is smooth
    // in log h (R ~ 1/h for spheres, h^-3/2 for discs), so Gauss-Legendre
    // in s = log h integrates R dh = R h ds to round-off in a few points.
    double integral = 0., from = lo;
    if (from < floor)
      {
        const double to = std::min(hi, floor);
        integral += resistance(floor) * (to - from);
        from = to;
      }
    if (hi > from)
      {
        static const std::array<double, 5> point  = {{0.,
                                                      -0.5384693101056831,
                                                      0.5384693101056831,
                                                      -0.9061798459386640,
                                                      0.9061798459386640}};
        static const std::array<double, 5> weight = {{0.5688888888888889,
                                                      0.4786286704993665,
                                                      0.4786286704993665,
                                                      0.2369268850561891,
                                                      0.2369268850561891}};
        const double s0 = std::log(from), s1 = std::log(hi);
        for (unsigned int q = 0; q < point.size(); ++q)
          {
            const double h =
              std::exp(0.5 * (s0 + s1) + 0.5 * (s1 - s0) * point[q]);
            integral += 0.5 * (s1 - s0) * weight[q] * resistance(h) * h;
          }
      }
    return integral / (hi - lo);
  }
} // namespace Fidus::Contact
