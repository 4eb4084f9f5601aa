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
//    (R with its logarithmic term) falls at first order (ratio of errors at
//    dt and dt/2 in [1.7, 2.3]).
// i. Non-finite input throws ContactError.
// j. A close pair turning as a doublet (relative velocity perpendicular to
//    the line of centres): an explicit Euler step with the velocities of
//    correct(..., dt) changes the distance by o^2 / l (fourth order in dt)
//    only, where the uncorrected step opens it by o = |w|^2 dt^2 / 2l.
//
// Tangential terms (LubricationSettings::tangential):
// k. The bond resistance (minus the derivative of the loads) is symmetric
//    and positive semi-definite, and zero for a rigid motion of the pair
//    (2D and 3D, unequal radii, and a wall moving with the particle).
// l. Known leading coefficients: a sphere sliding along a wall (force 8/15
//    of 6 pi eta a U log, torque 1/10 of 8 pi eta a^2 U log), rotating near
//    it (force 2/15 of 6 pi eta a^2 W log, torque 2/5 of 8 pi eta a^3 W log;
//    O'Neill & Stewartson 1967, Goldman, Cox & Brenner 1967), two equal
//    spheres (1/6, Jeffrey & Onishi 1984), a cylinder near a wall (force
//    and torque 2 sqrt(2) pi eta (a/h)^1/2, no coupling), 1e-12.
// m. 2D: the loads match a quadrature of the unsteady Reynolds equation of
//    the gap between the exact circles (unequal discs and a disc near a
//    wall; each surface sliding, rotating, and the gap's profile moving with
//    the discs), error below 4 % at h = 1e-4 R and falling with h.
// n. Through correct(): the stored forces and torques give
//    zeta (u - u*) and zeta_rot (w - w*) (1e-9), the forces are internal,
//    and a cluster translating with the sliding walls keeps u = u*, w = w*.
// o. A particle at rest under a sliding wall is dragged along; a sphere is
//    turned the way the wall turns it, a disc is not (no coupling at
//    leading order for a cylinder near a plane).

#include "test_tools.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fidus/contact/contact_error.h>
#include <fidus/lubrication/lubrication_correction.h>
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

  using Local = std::array<double, 12>;

  LubricationBond
  bond_of(const double a_i, const double a_j, const Vec3 &n)
  {
    LubricationBond b;
    b.a_i = a_i;
    b.a_j = a_j;
    b.n   = n;
    b.i   = 0;
    b.j   = a_j > 0. ? 1 : LubricationBond::no_particle;
    return b;
  }

  /// Resistance matrix -d(loads)/dv of the tangential terms of a bond.
  std::array<Local, 12>
  resistance_of(const LubricationBond &b, const unsigned dim, const double c)
  {
    std::array<Local, 12> R{};
    for (unsigned k = 0; k < 12; ++k)
      {
        Local e{};
        e[k]          = 1.;
        const Local f = LubricationCorrection::tangential_loads(b, c, dim, e);
        for (unsigned m = 0; m < 12; ++m)
          R[m][k] = -f[m];
      }
    return R;
  }

  void
  test_tangential_structure()
  {
    TestTools::Random rnd(5);
    for (const unsigned dim : {2u, 3u})
      for (const bool wall : {false, true})
        {
          Vec3 n{{rnd.uniform(-1, 1), rnd.uniform(-1, 1), 0.}};
          if (dim == 3)
            n[2] = rnd.uniform(-1, 1);
          const double norm = std::sqrt(dot(n, n));
          for (double &c : n)
            c /= norm;
          const double          a_i = 0.7, a_j = wall ? 0. : 1.3;
          const LubricationBond b    = bond_of(a_i, a_j, n);
          const unsigned        m    = wall ? 6 : 12;
          const auto            R    = resistance_of(b, dim, 1.);
          double                asym = 0., scale = 0.;
          for (unsigned k = 0; k < m; ++k)
            for (unsigned l = 0; l < m; ++l)
              {
                asym  = std::max(asym, std::abs(R[k][l] - R[l][k]));
                scale = std::max(scale, std::abs(R[k][l]));
              }
          // Positive semi-definite: x.Rx >= 0 for random x, in the plane
          // of motion in 2D.
          double min_form = 0.;
          for (int t = 0; t < 2000; ++t)
            {
              Local x{};
              for (unsigned k = 0; k < m; ++k)
                {
                  const bool in_plane =
                    dim == 3 || (k % 6 < 3 ? k % 3 < 2 : k % 3 == 2);
                  x[k] = in_plane ? rnd.uniform(-1, 1) : 0.;
                }
              double form = 0.;
              for (unsigned k = 0; k < m; ++k)
                for (unsigned l = 0; l < m; ++l)
                  form += x[k] * R[k][l] * x[l];
              min_form = std::min(min_form, form);
            }
          // A rigid motion: translation V and rotation W about i's centre,
          // j's centre at (a_i + a_j) n; for a wall, the particle moves
          // with the wall.
          Local v{};
          Vec3  V{{rnd.uniform(-1, 1), rnd.uniform(-1, 1), 0.}},
            W{{0., 0., rnd.uniform(-1, 1)}};
          if (dim == 3)
            {
              V[2] = rnd.uniform(-1, 1);
              W[0] = rnd.uniform(-1, 1);
              W[1] = rnd.uniform(-1, 1);
            }
          LubricationBond moving = b;
          for (unsigned d = 0; d < 3; ++d)
            {
              v[d] = V[d];
              if (!wall)
                {
                  v[3 + d]         = W[d];
                  v[9 + d]         = W[d];
                  const unsigned e = (d + 1) % 3, f = (d + 2) % 3;
                  v[6 + d] = V[d] + (a_i + a_j) * (W[e] * n[f] - W[f] * n[e]);
                }
            }
          moving.wall_velocity = V;
          double rigid         = 0.;
          for (const double f :
               LubricationCorrection::tangential_loads(moving, 1., dim, v))
            rigid = std::max(rigid, std::abs(f));
          const std::string what = std::to_string(dim) + "D " +
                                   (wall ? "wall" : "pair a_i/a_j = 0.7/1.3");
          check("k. tangential resistance, " + what +
                  ": symmetric, positive semi-definite, zero for a rigid "
                  "motion",
                asym < 1e-12 * scale && min_form > -1e-12 * scale &&
                  rigid < 1e-12 * scale);
        }
  }

  void
  test_tangential_coefficients()
  {
    const Vec3   n{{0., 1., 0.}}; // from i (below) to j or the wall (above)
    const double a = 0.8, eta = 1.3, h = 1e-3;
    const auto   load = [&](const LubricationBond &b,
                          const unsigned         dim,
                          const double           c,
                          const unsigned         k) {
      Local v{};
      v[k] = 1.;
      return LubricationCorrection::tangential_loads(b, c, dim, v);
    };
    bool       ok   = true;
    const auto near = [&](const double value, const double expected) {
      const bool good = std::abs(value - expected) < 1e-12 * std::abs(expected);
      if (!good)
        std::cout << "  " << value << " expected " << expected << std::endl;
      ok = ok && good;
    };
    // Sphere and wall: c = 2 pi eta a L, L the logarithm.
    {
      const LubricationBond b = bond_of(a, 0., n);
      const double          L = std::log(a / h);
      const double          c =
        LubricationCorrection::tangential_resistance(3, eta, a, 0., h, 0.);
      near(c, 2. * pi * eta * a * L);
      const Local slide = load(b, 3, c, 0), turn = load(b, 3, c, 5);
      near(slide[0] / (6. * pi * eta * a * L), -8. / 15.);
      near(std::abs(slide[5]) / (8. * pi * eta * a * a * L), 1. / 10.);
      near(std::abs(turn[0]) / (6. * pi * eta * a * a * L), 2. / 15.);
      near(turn[5] / (8. * pi * eta * a * a * a * L), -2. / 5.);
      // Reciprocity: the torque of sliding is the force of turning.
      near(slide[5], turn[0]);
    }
    // Two equal spheres, j at rest: 1/6 of 6 pi eta a L on i.
    {
      const LubricationBond b = bond_of(a, a, n);
      const double          L = std::log(0.5 * a / h);
      const double          c =
        LubricationCorrection::tangential_resistance(3, eta, a, a, h, 0.);
      near(load(b, 3, c, 0)[0] / (6. * pi * eta * a * L), -1. / 6.);
    }
    // Cylinder and wall: 2 sqrt(2) pi eta (a/h)^1/2, no coupling.
    {
      const LubricationBond b = bond_of(a, 0., n);
      const double          c =
        LubricationCorrection::tangential_resistance(2, eta, a, 0., h, 0.);
      const double K     = 2. * std::sqrt(2.) * pi * eta * std::sqrt(a / h);
      const Local  slide = load(b, 2, c, 0), turn = load(b, 2, c, 5);
      near(slide[0], -K);
      near(turn[5], -K * a * a);
      ok =
        ok && std::abs(slide[5]) < 1e-12 * K && std::abs(turn[0]) < 1e-12 * K;
    }
    check("l. tangential coefficients: sphere-wall 8/15, 1/10, 2/15, 2/5, "
          "equal spheres 1/6, cylinder-wall 2 sqrt(2) pi eta (a/h)^1/2",
          ok);
  }

  /**
   * Loads (F_jx, T_iz, T_jz) of the gap between a circle of radius a_i
   * below and one of radius a_j above (a_j = 0: a plane) at distance h, by
   * quadrature of the unsteady Reynolds equation with the exact circles:
   * surface velocities U1 = U_i - a_i w_i, U2 = U_j + a_j w_j, the gap's
   * profile moving with U_i and U_j, zero pressure at |x| = 0.9 min(a).
   */
  std::array<double, 3>
  reynolds_loads(const double a_i,
                 const double a_j,
                 const double h,
                 const Local &v)
  {
    const double eta = 1.3;
    const double U_i = v[0], w_i = v[5], U_j = v[6], w_j = v[11];
    const double U1 = U_i - a_i * w_i, U2 = U_j + a_j * w_j;
    const auto   g = [](const double r, const double x) {
      return r > 0. ? r - std::sqrt(r * r - x * x) : 0.;
    };
    const auto dg = [](const double r, const double x) {
      return r > 0. ? x / std::sqrt(r * r - x * x) : 0.;
    };
    const double a_min = a_j > 0. ? std::min(a_i, a_j) : a_i;
    const double s_max = std::cbrt(0.9 * a_min);
    const int    m     = 400000;
    // Points x_k from -X to X, denser near 0 (x = s^3).
    std::vector<double> x(2 * m + 1), wgt(2 * m + 1);
    for (int k = -m; k <= m; ++k)
      {
        const double s = s_max * k / m;
        x[k + m]       = s * s * s;
        wgt[k + m]     = 3. * s * s * s_max / m * (std::abs(k) == m ? 0.5 : 1.);
      }
    const auto H = [&](const double y) { return h + g(a_i, y) + g(a_j, y); };
    // p' = 6 eta (U1 + U2) / H^2 - 12 eta q / H^3, q = q0 + U_i g_i + U_j g_j
    double I2 = 0., I3 = 0., Ig = 0.;
    for (std::size_t k = 0; k < x.size(); ++k)
      {
        const double Hk = H(x[k]);
        I2 += wgt[k] / (Hk * Hk);
        I3 += wgt[k] / (Hk * Hk * Hk);
        Ig +=
          wgt[k] * (U_i * g(a_i, x[k]) + U_j * g(a_j, x[k])) / (Hk * Hk * Hk);
      }
    const double        q0 = (6. * (U1 + U2) * I2 - 12. * Ig) / (12. * I3);
    std::vector<double> dp(x.size()), p(x.size(), 0.);
    for (std::size_t k = 0; k < x.size(); ++k)
      {
        const double Hk = H(x[k]);
        const double q  = q0 + U_i * g(a_i, x[k]) + U_j * g(a_j, x[k]);
        dp[k] =
          6. * eta * (U1 + U2) / (Hk * Hk) - 12. * eta * q / (Hk * Hk * Hk);
      }
    for (std::size_t k = 1; k < x.size(); ++k)
      p[k] = p[k - 1] + 0.5 * (dp[k] + dp[k - 1]) * (x[k] - x[k - 1]);
    double F_j = 0., shear_u = 0., shear_l = 0.;
    for (std::size_t k = 0; k < x.size(); ++k)
      {
        const double Hk  = H(x[k]);
        const double tau = eta * (U2 - U1) / Hk;
        shear_u += wgt[k] * (tau + 0.5 * dp[k] * Hk);
        shear_l += wgt[k] * (tau - 0.5 * dp[k] * Hk);
        F_j -= wgt[k] * p[k] * dg(a_j, x[k]);
      }
    F_j -= shear_u;
    return {{F_j, -a_i * shear_l, -a_j * shear_u}};
  }

  void
  test_tangential_reynolds()
  {
    const Vec3 n{{0., 1., 0.}};
    for (const double a_j : {0.7, 0.})
      {
        const double          a_i = 1., eta = 1.3;
        const double          R = a_j > 0. ? a_i * a_j / (a_i + a_j) : a_i;
        const LubricationBond b = bond_of(a_i, a_j, n);
        double                err[2];
        int                   e = 0;
        for (const double h : {1e-3 * R, 1e-4 * R})
          {
            const double c     = LubricationCorrection::tangential_resistance(2,
                                                                          eta,
                                                                          a_i,
                                                                          a_j,
                                                                          h,
                                                                          0.);
            double       worst = 0.;
            for (const unsigned k : {0u, 5u, 6u, 11u})
              {
                if (a_j == 0. && k > 5)
                  continue;
                Local v{};
                v[k] = 1.;
                const Local f =
                  LubricationCorrection::tangential_loads(b, c, 2, v);
                const std::array<double, 3> model = {{f[6], f[5], f[11]}};
                const std::array<double, 3> exact =
                  reynolds_loads(a_i, a_j, h, v);
                double scale = 0.;
                for (const double y : exact)
                  scale = std::max(scale, std::abs(y));
                for (unsigned m = 0; m < 3; ++m)
                  if (a_j > 0. || m == 1)
                    worst =
                      std::max(worst, std::abs(model[m] - exact[m]) / scale);
              }
            err[e++] = worst;
          }
        const bool ok = err[1] < 0.04 && err[1] < err[0];
        if (!ok || std::getenv("FIDUS_TEST_VERBOSE"))
          std::cout << "  m. errors at h = 1e-3 R, 1e-4 R: " << err[0] << " "
                    << err[1] << std::endl;
        check(std::string("m. 2D tangential loads, ") +
                (a_j > 0. ? "discs a_j/a_i = 0.7" : "disc and wall") +
                ": match the unsteady Reynolds equation as h -> 0",
              ok);
      }
  }

  void
  test_tangential_correct()
  {
    for (const unsigned dim : {2u, 3u})
      {
        TestTools::Random   rnd(11 + dim);
        const double        h_c = 0.03;
        LubricationSettings s   = settings_of(dim, h_c);
        s.roughness             = 1e-3;
        s.tangential            = true;
        LubricationCorrection lub(s);
        Wall                  bottom, top;
        bottom.axis = top.axis = 1;
        bottom.position        = -0.5;
        bottom.side            = 1;
        top.position           = 0.5;
        top.side               = -1;
        const Vec3 V{{0.7, 0., dim == 3 ? -0.2 : 0.}};
        bottom.velocity = top.velocity = V;
        lub.set_walls({bottom, top});
        // A chain from the bottom wall to the top one.
        std::vector<Vec3>   x(1, Vec3{{0., -0.5 + 0.1 + 0.005, 0.}});
        std::vector<double> radii(1, 0.1);
        while (x.back()[1] + radii.back() < 0.5 - 0.12)
          {
            const double a  = rnd.uniform(0.05, 0.1);
            const double th = rnd.uniform(0.6, 1.2);
            const double ph = dim == 3 ? rnd.uniform(-0.5, 0.5) : 0.;
            const double d  = radii.back() + a + rnd.uniform(-2e-4, 0.02);
            Vec3         p  = x.back();
            p[0] += d * std::cos(th) * std::cos(ph);
            p[1] += d * std::sin(th) * std::cos(ph);
            p[2] += d * std::sin(ph);
            x.push_back(p);
            radii.push_back(a);
          }
        x.back()[1] = 0.5 - radii.back() - 0.004;
        std::vector<Vec3> u_star, w_star, u, w;
        for (std::size_t i = 0; i < x.size(); ++i)
          {
            u_star.push_back({{rnd.uniform(-1, 1),
                               rnd.uniform(-1, 1),
                               dim == 3 ? rnd.uniform(-1, 1) : 0.}});
            w_star.push_back({{dim == 3 ? rnd.uniform(-1, 1) : 0.,
                               dim == 3 ? rnd.uniform(-1, 1) : 0.,
                               rnd.uniform(-1, 1)}});
          }
        const LubricationStatistics st =
          lub.correct(x, radii, u_star, w_star, u, w);
        std::vector<Vec3> f(x.size(), Vec3{{0., 0., 0.}}), t = f;
        Vec3              total{{0., 0., 0.}};
        for (const LubricationBond &b : lub.bonds())
          for (unsigned d = 0; d < 3; ++d)
            {
              const double fj = b.force * b.n[d] + b.tangential_force[d];
              f[b.i][d] -= fj;
              t[b.i][d] += b.torque_i[d];
              if (b.j != LubricationBond::no_particle)
                {
                  f[b.j][d] += fj;
                  t[b.j][d] += b.torque_j[d];
                }
              else
                total[d] += fj; // the force on the wall
            }
        double f_max = 0., mismatch = 0.;
        for (std::size_t i = 0; i < x.size(); ++i)
          for (unsigned d = 0; d < 3; ++d)
            {
              const double df = lub.drag(radii[i]) * (u[i][d] - u_star[i][d]);
              const double dt =
                lub.rotational_drag(radii[i]) * (w[i][d] - w_star[i][d]);
              f_max = std::max({f_max, std::abs(f[i][d]), std::abs(t[i][d])});
              mismatch = std::max(
                {mismatch, std::abs(df - f[i][d]), std::abs(dt - t[i][d])});
              total[d] += f[i][d];
            }
        bool tangential = false;
        for (const LubricationBond &b : lub.bonds())
          tangential =
            tangential || dot(b.tangential_force, b.tangential_force) > 0.;
        // The same cluster translating with the walls, not turning.
        std::vector<Vec3> u_rigid(x.size(), V), w_rigid(x.size()), u2, w2;
        lub.correct(x, radii, u_rigid, w_rigid, u2, w2);
        double moved = 0.;
        for (std::size_t i = 0; i < x.size(); ++i)
          for (unsigned d = 0; d < 3; ++d)
            moved =
              std::max({moved, std::abs(u2[i][d] - V[d]), std::abs(w2[i][d])});
        const std::string D =
          "n. " + std::to_string(dim) + "D chain between sliding walls: ";
        check(D + "pair and wall bonds, CG converged, tangential forces",
              st.n_pairs > 3 && st.n_wall_pairs == 2 && st.converged &&
                tangential);
        check(D + "forces and torques give zeta (u - u*), zeta_rot (w - w*) "
                  "(1e-9)",
              f_max > 0. && mismatch < 1e-9 * f_max);
        check(D + "forces on particles and walls sum to zero (1e-9)",
              std::sqrt(dot(total, total)) < 1e-9 * f_max);
        check(D + "translating with the walls: u = u*, w = w* (1e-12)",
              moved < 1e-12);
      }
  }

  void
  test_tangential_wall_drag()
  {
    for (const unsigned dim : {2u, 3u})
      {
        LubricationSettings s = settings_of(dim, 0.02);
        s.tangential          = true;
        s.nothing_resolved    = true;
        LubricationCorrection lub(s);
        Wall                  top;
        top.axis     = 1;
        top.position = 1.;
        top.side     = -1;
        top.velocity = {{1., 0., 0.}};
        lub.set_walls({top});
        const double      a = 0.1;
        std::vector<Vec3> u, w;
        lub.correct({{{0.5, 1. - a - 1e-3, 0.}}},
                    {a},
                    {{{0., 0., 0.}}},
                    {{{0., 0., 0.}}},
                    u,
                    w);
        // In 2D sliding and turning decouple at leading order near a plane:
        // the disc is dragged but not turned; a sphere is turned.
        const bool turned = dim == 3 ? w[0][2] < 0. : std::abs(w[0][2]) < 1e-12;
        check("o. " + std::to_string(dim) +
                "D particle at rest under a sliding wall: dragged along "
                "(0 < u_x < V); a sphere turns clockwise (w_z < 0), a disc "
                "does not turn",
              u[0][0] > 0. && u[0][0] < 1. && turned &&
                std::abs(u[0][1]) < 1e-15);
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
    // Exact: the integral of zeta + 2 R(h) from h0 to h(T) equals
    // -v (zeta + 2 Rres) T, with R(h) = C / h + D ln(a / h) for two equal
    // spheres (3D; D = 6 pi eta a 9/40), solved for h(T) by bisection.
    const double a = 0.1, h0 = 0.01, h_c = 0.02, v = 1., T = 0.025, eta = 1.3;
    const double zeta = 6. * pi * eta * a;
    const double C    = 6. * pi * eta * (a / 2) * (a / 2);
    const double D    = 6. * pi * eta * a * 9. / 40.;
    const double Rres = C / h_c + D * std::log(a / h_c);
    const auto   F    = [&](const double h) { // an antiderivative of R
      return C * std::log(h) + D * h * (std::log(a / h) + 1.);
    };
    const auto g = [&](const double h) {
      return zeta * (h - h0) + 2. * (F(h) - F(h0)) + v * (zeta + 2. * Rres) * T;
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
  test_tangential_structure();
  test_tangential_coefficients();
  test_tangential_reynolds();
  test_tangential_correct();
  test_tangential_wall_drag();
  return TestTools::failures() != 0;
}
