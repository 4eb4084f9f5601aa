// Sub-grid lubrication correction (LubricationCorrection), against known
// answers:
//
// a. The squeeze resistance of two discs, two spheres, a disc and a wall, a
//    sphere and a wall equals the Reynolds integral of the gap between the
//    exact circles (computed here by quadrature, no paraboloid assumed): the
//    ratio tends to 1 as the gap closes (relative error below 3 % at
//    h = 1e-4 R and smaller than at 1e-3 R).
// b. A head-on pair of equal particles (2D and 3D): the closing speed is
//    multiplied by (zeta + 2 Rres) / (zeta + 2 R), the tangential velocity
//    is unchanged, 1e-12.
// c. A particle closing on a wall: (zeta + Rres) / (zeta + R), 1e-12.
// d. A random cluster (2D and 3D, unequal radii): the CG converges, the
//    stored bond forces reproduce the velocity change zeta_i (u_i - u*_i) of
//    every particle (1e-9 of the largest), the forces are internal (their
//    sum is 1e-9 of the largest), and every bond's resistances are those of
//    its gap (capped by the roughness) and of the range.
// e. Pairs at or beyond the range, and an isolated particle: u = u*
//    exactly.
// f. Periodic: a pair across the periodic face gives the same velocities as
//    the same pair shifted into the box (1e-12).
// g. Roughness: a gap below roughness * a counts as that gap.
// h. Stability and order: two spheres squeezed at constant u* (explicit
//    Euler in position, the correction implicit in velocity): the gap stays
//    positive at a time step with dt v < 1 / (1/h_c + 2/a), and its error
//    against the exact solution of dh/dt = -v (zeta + 2 Rres) / (zeta + 2 R(h))
//    falls at first order (ratio of errors at dt and dt/2 in [1.7, 2.3]).
// i. Non-finite input throws ContactError.
// j. A close pair turning as a doublet (relative velocity perpendicular to
//    the line of centres): an explicit Euler step with the velocities of
//    correct(..., dt) changes the distance by o^2 / l (fourth order in dt)
//    only, where the uncorrected step opens it by o = |w|^2 dt^2 / 2l.

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/lubrication_correction.h>
#include <iostream>
#include <string>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  constexpr double pi = 3.14159265358979323846;

  /**
   * Reynolds squeeze force per unit closing speed for the gap between two
   * circles of radii a1, a2 (a2 = 0: a plane) at distance h, by quadrature
   * of the exact gap height H(x) = h + a1 - sqrt(a1^2 - x^2) + (same for
   * a2) over |x| < 0.9 min(a): in 2D, F = int 12 eta x^2 / H^3 dx; in 3D
   * (axisymmetric), F = int_0 6 pi eta r^3 / H^3 dr.
   */
  double
  reynolds_force(const unsigned dim,
                 const double   a1,
                 const double   a2,
                 const double   h)
  {
    const double a_min = a2 > 0. ? std::min(a1, a2) : a1;
    const auto   H     = [&](const double x) {
      double g = h + a1 - std::sqrt(a1 * a1 - x * x);
      if (a2 > 0.)
        g += a2 - std::sqrt(a2 * a2 - x * x);
      return g;
    };
    // Substitution x = s^3 puts many points near x = 0, where H is small.
    const double s_max = std::cbrt(0.9 * a_min);
    const int    m     = 400000;
    double       sum   = 0.;
    for (int k = 0; k <= m; ++k)
      {
        const double s  = s_max * k / m;
        const double x  = s * s * s;
        const double dx = 3. * s * s * s_max / m;
        const double w  = (k == 0 || k == m) ? 0.5 : 1.;
        const double f  = dim == 2 ? 2. * 12. * x * x / std::pow(H(x), 3) :
                                     6. * pi * x * x * x / std::pow(H(x), 3);
        sum += w * f * dx;
      }
    return sum;
  }

  LubricationSettings
  settings_of(const unsigned dim, const double range)
  {
    LubricationSettings s;
    s.dimension = dim;
    s.viscosity = 1.3;
    s.range     = range;
    s.roughness = 0.;
    return s;
  }

  double
  dot(const Vec3 &a, const Vec3 &b)
  {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }

  void
  test_resistance()
  {
    for (const unsigned dim : {2u, 3u})
      for (const double a2 : {0.7, 0.})
        {
          const double a1 = 1.;
          const double R  = a2 > 0. ? a1 * a2 / (a1 + a2) : a1;
          double       err[2];
          int          k = 0;
          for (const double h : {1e-3 * R, 1e-4 * R})
            {
              const double exact = reynolds_force(dim, a1, a2, h);
              const double model =
                LubricationCorrection::squeeze_resistance(dim, 1., a1, a2, h);
              err[k++] = std::abs(model / exact - 1.);
            }
          const std::string what = std::to_string(dim) + "D " +
                                   (a2 > 0. ? "pair a2/a1 = 0.7" : "wall");
          const bool ok = err[1] < 0.03 && err[1] < err[0];
          if (!ok)
            std::cout << "  errors " << err[0] << " " << err[1] << std::endl;
          check("a. squeeze resistance, " + what +
                  ": matches the Reynolds integral as h -> 0",
                ok);
        }
  }

  void
  test_head_on()
  {
    for (const unsigned dim : {2u, 3u})
      {
        const double              a = 0.1, h = 1e-3, h_c = 0.02;
        LubricationSettings       s = settings_of(dim, h_c);
        LubricationCorrection     lub(s);
        const std::vector<Vec3>   x     = {{{0.3, 0.4, 0.}},
                                           {{0.3 + 2 * a + h, 0.4, 0.}}};
        const std::vector<double> radii = {a, a};
        const std::vector<Vec3> u_star = {{{0.5, 0.2, 0.}}, {{-0.5, -0.1, 0.}}};
        std::vector<Vec3>       u;
        const LubricationStatistics st   = lub.correct(x, radii, u_star, u);
        const double                zeta = lub.drag(a);
        const double                R =
          LubricationCorrection::squeeze_resistance(dim, 1.3, a, a, h);
        const double Rres =
          LubricationCorrection::squeeze_resistance(dim, 1.3, a, a, h_c);
        const double factor  = (zeta + 2. * Rres) / (zeta + 2. * R);
        const double closing = u[0][0] - u[1][0];
        const bool   ok      = st.n_pairs == 1 && st.converged &&
                        std::abs(closing - 1.0 * factor) < 1e-12 &&
                        std::abs(u[0][0] + u[1][0]) < 1e-12 && u[0][1] == 0.2 &&
                        u[1][1] == -0.1;
        if (!ok)
          std::cout << "  closing " << closing << " expected " << factor
                    << std::endl;
        check("b. " + std::to_string(dim) +
                "D head-on pair: closing speed times (zeta + 2 Rres) / "
                "(zeta + 2 R), tangential unchanged",
              ok);
      }
  }

  void
  test_wall()
  {
    for (const unsigned dim : {2u, 3u})
      {
        const double          a = 0.1, h = 2e-3, h_c = 0.02;
        LubricationSettings   s = settings_of(dim, h_c);
        LubricationCorrection lub(s);
        Wall                  w;
        w.axis     = 1;
        w.position = 1.;
        w.side     = -1; // upper wall: particles below it
        w.velocity = {{0.5, 0., 0.}};
        lub.set_walls({w});
        const std::vector<Vec3>     x      = {{{0.3, 1. - a - h, 0.}}};
        const std::vector<double>   radii  = {a};
        const std::vector<Vec3>     u_star = {{{0.1, 0.3, 0.}}};
        std::vector<Vec3>           u;
        const LubricationStatistics st   = lub.correct(x, radii, u_star, u);
        const double                zeta = lub.drag(a);
        const double                R =
          LubricationCorrection::squeeze_resistance(dim, 1.3, a, 0., h);
        const double Rres =
          LubricationCorrection::squeeze_resistance(dim, 1.3, a, 0., h_c);
        const double expected = 0.3 * (zeta + Rres) / (zeta + R);
        const bool   ok       = st.n_wall_pairs == 1 &&
                        std::abs(u[0][1] - expected) < 1e-12 && u[0][0] == 0.1;
        check("c. " + std::to_string(dim) +
                "D particle closing on a wall: speed times (zeta + Rres) / "
                "(zeta + R)",
              ok);
      }
  }

  void
  test_cluster()
  {
    for (const unsigned dim : {2u, 3u})
      {
        TestTools::Random   rnd(7 + dim);
        const double        h_c = 0.03;
        LubricationSettings s   = settings_of(dim, h_c);
        s.roughness             = 1e-3;
        LubricationCorrection lub(s);
        // A loose chain of touching-ish particles along a wavy line.
        std::vector<Vec3>   x(1, Vec3{{0., 0., 0.}});
        std::vector<double> radii(1, 0.1);
        std::vector<Vec3>   u_star;
        for (int k = 1; k < 40; ++k)
          {
            const double a  = rnd.uniform(0.06, 0.12);
            const double th = rnd.uniform(-0.8, 0.8);
            const double ph = dim == 3 ? rnd.uniform(-0.8, 0.8) : 0.;
            const double d  = radii.back() + a + rnd.uniform(-2e-4, 0.03);
            Vec3         p  = x.back();
            p[0] += d * std::cos(th) * std::cos(ph);
            p[1] += d * std::sin(th) * std::cos(ph);
            p[2] += d * std::sin(ph);
            x.push_back(p);
            radii.push_back(a);
          }
        for (std::size_t i = 0; i < x.size(); ++i)
          u_star.push_back({{rnd.uniform(-1, 1),
                             rnd.uniform(-1, 1),
                             dim == 3 ? rnd.uniform(-1, 1) : 0.}});
        std::vector<Vec3>           u;
        const LubricationStatistics st = lub.correct(x, radii, u_star, u);
        std::vector<Vec3>           f(x.size(), Vec3{{0., 0., 0.}});
        for (const LubricationBond &b : lub.bonds())
          for (unsigned d = 0; d < 3; ++d)
            {
              f[b.i][d] -= b.force * b.n[d];
              f[b.j][d] += b.force * b.n[d];
            }
        double f_max = 0., mismatch = 0.;
        Vec3   total{{0., 0., 0.}};
        for (std::size_t i = 0; i < x.size(); ++i)
          for (unsigned d = 0; d < 3; ++d)
            {
              const double change =
                lub.drag(radii[i]) * (u[i][d] - u_star[i][d]);
              f_max    = std::max(f_max, std::abs(f[i][d]));
              mismatch = std::max(mismatch, std::abs(change - f[i][d]));
              total[d] += change;
            }
        const double total_norm  = std::sqrt(dot(total, total));
        bool         resistances = true;
        for (const LubricationBond &b : lub.bonds())
          {
            const double a1 = radii[b.i], a2 = radii[b.j];
            const double gap = std::max(b.gap, s.roughness * std::min(a1, a2));
            const double R =
              LubricationCorrection::squeeze_resistance(dim, 1.3, a1, a2, gap);
            const double Rres =
              LubricationCorrection::squeeze_resistance(dim, 1.3, a1, a2, h_c);
            if (std::abs(b.r_true - R) > 1e-12 * R ||
                std::abs(b.r_resolved - Rres) > 1e-12 * Rres || b.gap >= h_c)
              resistances = false;
          }
        const std::string D = std::to_string(dim) + "D cluster: ";
        check(D + "bonds found and CG converged",
              st.n_pairs > 10 && st.n_rough > 0 && st.converged);
        check(D + "bond forces give zeta (u - u*) (1e-9)",
              f_max > 0. && mismatch < 1e-9 * f_max);
        check(D + "forces are internal (1e-9)", total_norm < 1e-9 * f_max);
        check(D + "resistances of the gap and of the range", resistances);
      }
  }

  void
  test_out_of_range()
  {
    LubricationSettings         s = settings_of(3, 0.01);
    LubricationCorrection       lub(s);
    const std::vector<Vec3>     x      = {{{0., 0., 0.}},
                                          {{0.215, 0., 0.}},
                                          {{5., 5., 5.}}};
    const std::vector<double>   radii  = {0.1, 0.1, 0.2};
    const std::vector<Vec3>     u_star = {{{1., 2., 3.}},
                                          {{-1., 0.5, 0.}},
                                          {{4., 4., 4.}}};
    std::vector<Vec3>           u;
    const LubricationStatistics st = lub.correct(x, radii, u_star, u);
    check("e. pair at the range and isolated particle: u = u* exactly",
          st.n_pairs == 0 && u == u_star);
  }

  void
  test_periodic()
  {
    for (const unsigned dim : {2u, 3u})
      {
        LubricationSettings   s = settings_of(dim, 0.02);
        LubricationCorrection across(s), inside(s);
        across.set_periodicity({{1., 0., dim == 3 ? 1. : 0.}});
        inside.set_periodicity({{1., 0., dim == 3 ? 1. : 0.}});
        const double              h = 3e-3, a = 0.1;
        const std::vector<double> radii = {a, 0.08};
        const std::vector<Vec3>   x1    = {{{0.95, 0.5, 0.3}},
                                           {{0.95 + a + 0.08 + h - 1., 0.51, 0.3}}};
        const std::vector<Vec3>   x2    = {{{0.45, 0.5, 0.3}},
                                           {{0.45 + a + 0.08 + h, 0.51, 0.3}}};
        const std::vector<Vec3> u_star  = {{{0.7, 0.1, 0.}}, {{-0.2, 0.3, 0.}}};
        std::vector<Vec3>       u1, u2;
        across.correct(x1, radii, u_star, u1);
        inside.correct(x2, radii, u_star, u2);
        double diff = 0.;
        for (int i = 0; i < 2; ++i)
          for (int d = 0; d < 3; ++d)
            diff = std::max(diff, std::abs(u1[i][d] - u2[i][d]));
        check("f. " + std::to_string(dim) +
                "D pair across the periodic face: same as inside (1e-12)",
              across.bonds().size() == 1 && diff < 1e-12 && u1 != u_star);
      }
  }

  void
  test_roughness()
  {
    LubricationSettings s = settings_of(3, 0.02);
    s.roughness           = 1e-2;
    LubricationCorrection       lub(s);
    const double                a = 0.1;
    const std::vector<Vec3>     x = {{{0., 0., 0.}}, {{2 * a + 1e-5, 0., 0.}}};
    const std::vector<double>   radii  = {a, a};
    const std::vector<Vec3>     u_star = {{{1., 0., 0.}}, {{-1., 0., 0.}}};
    std::vector<Vec3>           u;
    const LubricationStatistics st = lub.correct(x, radii, u_star, u);
    const double                R =
      LubricationCorrection::squeeze_resistance(3, 1.3, a, a, 1e-2 * a);
    check("g. gap below the roughness counts as the roughness",
          st.n_rough == 1 && std::abs(lub.bonds()[0].r_true - R) < 1e-12 * R);
  }

  /// Gap after time T of two spheres squeezed at closing speed v.
  double
  squeeze(const double dt, const double T, double &min_gap)
  {
    const double              a = 0.1, h0 = 0.01, h_c = 0.02, v = 1.;
    LubricationSettings       s = settings_of(3, h_c);
    LubricationCorrection     lub(s);
    std::vector<Vec3>         x      = {{{0., 0., 0.}}, {{2 * a + h0, 0., 0.}}};
    const std::vector<double> radii  = {a, a};
    const std::vector<Vec3>   u_star = {{{0.5 * v, 0., 0.}},
                                        {{-0.5 * v, 0., 0.}}};
    std::vector<Vec3>         u;
    const int                 steps = static_cast<int>(std::lround(T / dt));
    min_gap                         = h0;
    for (int k = 0; k < steps; ++k)
      {
        lub.correct(x, radii, u_star, u);
        x[0][0] += dt * u[0][0];
        x[1][0] += dt * u[1][0];
        min_gap = std::min(min_gap, x[1][0] - x[0][0] - 2 * a);
      }
    return x[1][0] - x[0][0] - 2 * a;
  }

  void
  test_squeeze_order()
  {
    // Exact: (zeta h + 2C ln h) from h0 to h(T) = -v (zeta + 2 Rres) T,
    // R(h) = C / h (3D), solved for h(T) by bisection.
    const double a = 0.1, h0 = 0.01, h_c = 0.02, v = 1., T = 0.025, eta = 1.3;
    const double zeta = 6. * pi * eta * a;
    const double C    = 6. * pi * eta * (a / 2) * (a / 2);
    const double Rres = C / h_c;
    const auto   g    = [&](const double h) {
      return zeta * (h - h0) + 2. * C * std::log(h / h0) +
             v * (zeta + 2. * Rres) * T;
    };
    double lo = 1e-12, hi = h0;
    for (int k = 0; k < 200; ++k)
      (g(0.5 * (lo + hi)) > 0. ? hi : lo) = 0.5 * (lo + hi);
    const double exact = 0.5 * (lo + hi);
    double       min1, min2;
    const double dt  = 2.5e-3; // dt v < 1 / (1/h_c + 2/a)
    const double e1  = std::abs(squeeze(dt, T, min1) - exact);
    const double e2  = std::abs(squeeze(dt / 2, T, min2) - exact);
    const double rat = e1 / e2;
    const bool   ok  = min1 > 0. && min2 > 0. && rat > 1.7 && rat < 2.3;
    if (!ok)
      std::cout << "  exact " << exact << " errors " << e1 << " " << e2
                << " min gaps " << min1 << " " << min2 << std::endl;
    check("h. squeezed spheres: gap stays positive, first order in dt", ok);
    std::cout << "   (the exact gap closes to "
              << std::lround(100. * exact / h0) << " % of h0)" << std::endl;
  }

  void
  test_bad_input()
  {
    LubricationCorrection     lub(settings_of(2, 0.02));
    const std::vector<Vec3>   x      = {{{0., 0., 0.}}, {{0.2, 0., 0.}}};
    const std::vector<double> radii  = {0.1, 0.1};
    const std::vector<Vec3>   u_star = {{{NAN, 0., 0.}}, {{0., 0., 0.}}};
    std::vector<Vec3>         u;
    bool                      thrown = false;
    try
      {
        lub.correct(x, radii, u_star, u);
      }
    catch (const ContactError &e)
      {
        thrown = std::string(e.what()).find("particle 0") != std::string::npos;
      }
    check("i. a NaN velocity is reported with the particle", thrown);
  }
  void
  test_doublet_step()
  {
    for (const unsigned dim : {2u, 3u})
      {
        LubricationSettings     s = settings_of(dim, 0.02);
        LubricationCorrection   lub(s);
        const double            a = 0.1, h = 1e-3, dt = 0.1, l = 2 * a + h;
        const std::vector<Vec3> x = {{{0.2, 0.3, 0.1}}, {{0.2 + l, 0.3, 0.1}}};
        const std::vector<double> radii = {a, a};
        const std::vector<Vec3> u_star  = {{{0., -0.05, 0.}}, {{0., 0.05, 0.}}};
        std::vector<Vec3>       u0, u1;
        lub.correct(x, radii, u_star, u0);
        lub.correct(x, radii, u_star, u1, dt);
        const auto distance = [&](const std::vector<Vec3> &u) {
          double r2 = 0.;
          for (unsigned d = 0; d < 3; ++d)
            {
              const double r = x[1][d] + dt * u[1][d] - x[0][d] - dt * u[0][d];
              r2 += r * r;
            }
          return std::sqrt(r2);
        };
        const double opening = 0.1 * 0.1 * dt * dt / (2 * l);
        const bool   ok =
          std::abs(distance(u0) - l - opening) < 0.01 * opening &&
          std::abs(distance(u1) - l) < 1.01 * opening * opening / l;
        if (!ok)
          std::cout << "  distances " << distance(u0) - l << " "
                    << distance(u1) - l << std::endl;
        check("j. " + std::to_string(dim) +
                "D doublet: the Euler step keeps the distance with dt",
              ok);
      }
  }
} // namespace

int
main()
{
  test_resistance();
  test_head_on();
  test_wall();
  test_cluster();
  test_out_of_range();
  test_periodic();
  test_roughness();
  test_squeeze_order();
  test_bad_input();
  test_doublet_step();
  return TestTools::failures() != 0;
}
