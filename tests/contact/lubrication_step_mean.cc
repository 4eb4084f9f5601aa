// The lubrication correction's squeeze averaged over the step
// (LubricationSettings::gap_in_time, 'Fluid/Lubrication gap in time =
// step mean'). A head-on pair of equal spheres (3D) or discs (2D), driven by
// the flow only: the mesh's response closes it at w* = 2 D / (zeta + 2 R(h_f)),
// and the correction's model of the true motion is the squeeze equation
//
//   dh/dt = -2 D / (zeta + 2 R(max(h, delta))),
//
// whose time from h_0 to h_1 is T(h_1) = (zeta (h_0 - h_1) + 2 int_{h_1}^{h_0}
// R(max(h, delta)) dh) / (2 D) (delta the roughness floor). One explicit
// step with the resistance averaged over [h_1, h_0] lands exactly on the
// h_1 with T(h_1) = dt, for any dt. Checked against T computed here by a
// fine quadrature (independent of the code's):
//
// a. A step that, with the start's resistance, would close more than the
//    whole gap (the explicit end gap is negative): with the mean, the end gap
//    is positive and T(h_1) = dt to 1e-3 of dt.
// b. A step that closes a fifth of the gap: T(h_1) = dt to 1e-3.
// c. An opening pair (the flow pulls it apart, D < 0): T(h_1) = dt to 1e-3.
// d. A step that crosses the roughness floor (the resistance constant below
//    it): T(h_1) = dt to 1e-3, the end gap below the floor.
// e. A short step: the corrected closing speed is the start's to 1e-3 (the
//    mean is taken over a small interval).
// f. 'closing mean': the closing pair of a lands where 'step mean' puts it
//    (1e-12), the opening pair of c moves at the start's speed (1e-12).

#include "test_tools.h"

#include <cmath>
#include <fidus/lubrication/lubrication_correction.h>
#include <iostream>
#include <string>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  constexpr double eta = 1.3, a = 0.1, h_f = 0.05 * a;

  double
  resistance(const unsigned dim, const double gap)
  {
    return LubricationCorrection::squeeze_resistance(dim, eta, a, a, gap);
  }

  /// One step of size @p dt of a head-on pair at gap @p h0 driven by @p drive
  /// (positive closes it), with the resistance averaged over the step and
  /// the roughness @p roughness (of the radius): the end gap.
  double
  end_gap(const unsigned  dim,
          const double    h0,
          const double    drive,
          const double    dt,
          const double    roughness,
          const GapInTime gap_in_time = GapInTime::step_mean)
  {
    LubricationSettings s;
    s.dimension   = dim;
    s.viscosity   = eta;
    s.range       = h_f;
    s.flow_range  = h_f;
    s.roughness   = roughness;
    s.tangential  = false;
    s.gap_in_time = gap_in_time;
    LubricationCorrection   lub(s);
    const double            zeta = lub.drag(a);
    const double            w = 2. * drive / (zeta + 2. * resistance(dim, h_f));
    const std::vector<Vec3> x = {{{0.3, 0.4, 0.}},
                                 {{0.3 + 2 * a + h0, 0.4, 0.}}};
    const std::vector<Vec3> u_star = {{{0.5 * w, 0.1, 0.}},
                                      {{-0.5 * w, 0.1, 0.}}};
    std::vector<Vec3>       u;
    const auto              stat = lub.correct(x, {a, a}, u_star, u, dt);
    if (!stat.converged)
      std::cout << "the correction's solve did not converge" << std::endl;
    return h0 - dt * (u[0][0] - u[1][0]);
  }

  /// T(h1) of the squeeze equation above, by the midpoint rule on 200 000
  /// intervals in log h above the floor and exactly below it.
  double
  time_to(const unsigned dim,
          const double   h0,
          const double   h1,
          const double   drive,
          const double   roughness)
  {
    LubricationSettings s;
    s.dimension        = dim;
    s.viscosity        = eta;
    const double zeta  = LubricationCorrection(s).drag(a);
    const double floor = roughness * a;
    const double lo = std::min(h0, h1), hi = std::max(h0, h1);
    double       integral = 0., from = lo;
    if (from < floor)
      {
        integral += resistance(dim, floor) * (std::min(hi, floor) - from);
        from = std::min(hi, floor);
      }
    const unsigned int n  = 200000;
    const double       ds = std::log(hi / from) / n;
    for (unsigned int k = 0; k < n; ++k)
      {
        const double h = from * std::exp((k + 0.5) * ds);
        integral += resistance(dim, h) * h * ds;
      }
    const double sign = h0 > h1 ? 1. : -1.;
    return sign * (zeta * (hi - lo) + 2. * integral) / (2. * drive);
  }
} // namespace

int
main()
{
  for (const unsigned dim : {2u, 3u})
    {
      const std::string   D  = std::to_string(dim) + "D: ";
      const double        h0 = 0.01 * a, roughness = 1e-3;
      LubricationSettings s;
      s.dimension       = dim;
      s.viscosity       = eta;
      const double zeta = LubricationCorrection(s).drag(a);
      // The drive that closes h0 at the start's speed in a time 1.
      const double drive = 0.5 * h0 * (zeta + 2. * resistance(dim, h0));

      const double dt_a = 1.5;
      const double h_a  = end_gap(dim, h0, drive, dt_a, roughness);
      check(D + "a. a step that would close the gap 1.5 times: end gap "
                "positive, T(h_1) = dt",
            h_a > roughness * a &&
              std::abs(time_to(dim, h0, h_a, drive, roughness) - dt_a) <
                1e-3 * dt_a);

      const double dt_b = 0.2;
      const double h_b  = end_gap(dim, h0, drive, dt_b, roughness);
      check(D + "b. a step that closes a fifth: T(h_1) = dt",
            std::abs(time_to(dim, h0, h_b, drive, roughness) - dt_b) <
              1e-3 * dt_b);

      const double h_c = end_gap(dim, h0, -drive, dt_b, roughness);
      check(D + "c. an opening pair: T(h_1) = dt, the gap grows",
            h_c > h0 && std::abs(time_to(dim, h0, h_c, -drive, roughness) -
                                 dt_b) < 1e-3 * dt_b);

      // The floor at 0.8 h0: the step of a crosses it.
      const double rough_d = 0.8 * h0 / a;
      const double h_d     = end_gap(dim, h0, drive, dt_a, rough_d);
      check(D + "d. across the roughness floor: T(h_1) = dt, end below it",
            h_d < rough_d * a &&
              std::abs(time_to(dim, h0, h_d, drive, rough_d) - dt_a) <
                1e-3 * dt_a);

      const double dt_e = 1e-4;
      const double h_e  = end_gap(dim, h0, drive, dt_e, roughness);
      check(D + "e. a short step: the start's closing speed",
            std::abs((h0 - h_e) / dt_e - h0) < 1e-3 * h0);

      const double h_fa =
        end_gap(dim, h0, drive, dt_a, roughness, GapInTime::closing_mean);
      const double h_fc =
        end_gap(dim, h0, -drive, dt_b, roughness, GapInTime::closing_mean);
      const double h_start =
        end_gap(dim, h0, -drive, dt_b, roughness, GapInTime::start);
      check(D + "f. closing mean: closing as step mean, opening as start",
            std::abs(h_fa - h_a) < 1e-12 * h0 &&
              std::abs(h_fc - h_start) < 1e-12 * h0 &&
              std::abs(h_start - (h0 + dt_b * h0)) < 1e-12 * h0);
    }
  return TestTools::failures() != 0;
}
