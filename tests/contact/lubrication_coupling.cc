// The sub-grid lubrication solved with the flow (Contact::
// LubricationCoupling, `Fluid/Lubrication coupling = with the flow`),
// against a model fluid whose answer is known in closed form: each particle
// has the drag zeta_f = 2.5 zeta (zeta the isolated drag) and each bond the
// resolved resistance R_res of the correction (LubricationCorrection::
// resolved_loads), so that the fluid's rigid velocities under loads L are
// y = (zeta_f + R_res)^-1 (zeta_f u* + L) for the undisturbed shear u*. The
// coupled velocities x = y(L(x)) then solve (zeta_f + R_true) x = zeta_f u*
// + w (w: the forcing of a sliding wall), which is what the correction
// after the solve gives with its drag set to zeta_f and the fluid's
// unloaded velocities as its prediction. Three discs (spheres in 3D) in a
// chain of gaps below the range, the first near a wall sliding at 0.3,
// and one far from all:
//
// a. the iteration x <- x + P (y(L(x)) - x) of the coupling converges to
//    the correction's answer (relative error 1e-9) in at most 80 steps:
//    its error contracts by (Z + D)^-1 (I - Z M) D, and Z M lies in
//    [0.4, 1] here;
// b. with the coupling's drag equal to the fluid's (Z = M^-1) one step
//    gives it (relative error 1e-9);
// c. the far particle keeps its undisturbed velocity (no bond: 1e-12) and
//    the loads of the coupled velocities sum to the wall's force only (the
//    pair loads cancel: |sum of pair forces| < 1e-9 of the largest).

#include "test_tools.h"

#include <array>
#include <cmath>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/lubrication/lubrication_coupling.h>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  constexpr double eta = 1.3, a = 0.1, rate = 1., fluid_factor = 2.5;
  const double     pi = std::acos(-1.);

  using Local = std::array<double, 12>;

  LubricationSettings
  settings(const unsigned int dim, const double drag)
  {
    LubricationSettings s;
    s.dimension  = dim;
    s.viscosity  = eta;
    s.range      = 0.02;
    s.flow_range = 0.02; // one resolved resistance for flow and forces
    s.roughness  = 0.;
    s.tangential = true;
    s.drag       = drag;
    s.tolerance  = 1e-14;
    return s;
  }

  bool
  is_wall(const LubricationBond &b)
  {
    return b.j == LubricationBond::no_particle;
  }

  Local
  gather(const LubricationBond &b, const std::vector<double> &x)
  {
    Local l{};
    for (unsigned int k = 0; k < 6; ++k)
      {
        l[k] = x[6 * b.i + k];
        if (!is_wall(b))
          l[6 + k] = x[6 * b.j + k];
      }
    return l;
  }

  /// The model fluid: y = (zeta_f + R_res)^-1 rhs, by Gaussian elimination
  /// on the dense matrix (the unknowns of the dimension only).
  struct ModelFluid
  {
    ModelFluid(const LubricationCorrection &c,
               const std::size_t            n,
               const unsigned int           dim)
      : n(n)
    {
      for (unsigned int k = 0; k < 6 * n; ++k)
        if ((dim == 3) || (k % 6 == 0 || k % 6 == 1 || k % 6 == 5))
          active.push_back(k);
      zeta_f              = fluid_factor * c.drag(a);
      zeta_f_rot          = fluid_factor * c.rotational_drag(a);
      const std::size_t m = active.size();
      A.assign(m, std::vector<double>(m, 0.));
      for (std::size_t q = 0; q < m; ++q)
        {
          std::vector<double> e(6 * n, 0.), y(6 * n, 0.);
          e[active[q]] = 1.;
          y[active[q]] = active[q] % 6 < 3 ? zeta_f : zeta_f_rot;
          for (const LubricationBond &b : c.bonds())
            {
              const Local g = c.resolved_loads(b, gather(b, e));
              for (unsigned int k = 0; k < 6; ++k)
                {
                  y[6 * b.i + k] -= g[k];
                  if (!is_wall(b))
                    y[6 * b.j + k] -= g[6 + k];
                }
            }
          for (std::size_t p = 0; p < m; ++p)
            A[p][q] = y[active[p]];
        }
    }

    std::vector<double>
    solve(const std::vector<double> &rhs) const
    {
      const std::size_t                m = active.size();
      std::vector<std::vector<double>> M = A;
      std::vector<double>              b(m), v(m), x(6 * n, 0.);
      for (std::size_t p = 0; p < m; ++p)
        b[p] = rhs[active[p]];
      for (std::size_t k = 0; k < m; ++k)
        for (std::size_t l = k + 1; l < m; ++l)
          {
            const double f = M[l][k] / M[k][k];
            for (std::size_t q = k; q < m; ++q)
              M[l][q] -= f * M[k][q];
            b[l] -= f * b[k];
          }
      for (std::size_t k = m; k-- > 0;)
        {
          double s = b[k];
          for (std::size_t q = k + 1; q < m; ++q)
            s -= M[k][q] * v[q];
          v[k] = s / M[k][k];
        }
      for (std::size_t p = 0; p < m; ++p)
        x[active[p]] = v[p];
      return x;
    }

    /// y(L) for the loads @p force, @p torque on top of zeta_f u*.
    std::vector<double>
    velocities(const std::vector<double> &u_star,
               const std::vector<Vec3>   &force,
               const std::vector<Vec3>   &torque) const
    {
      std::vector<double> rhs(6 * n);
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          {
            rhs[6 * i + d] = zeta_f * u_star[6 * i + d] + force[i][d];
            rhs[6 * i + 3 + d] =
              zeta_f_rot * u_star[6 * i + 3 + d] + torque[i][d];
          }
      return solve(rhs);
    }

    std::size_t                      n;
    std::vector<unsigned int>        active;
    double                           zeta_f = 0., zeta_f_rot = 0.;
    std::vector<std::vector<double>> A;
  };

  double
  relative_difference(const std::vector<double> &x,
                      const std::vector<double> &y)
  {
    double d = 0., s = 0.;
    for (std::size_t k = 0; k < x.size(); ++k)
      {
        if (!std::isfinite(x[k]) || !std::isfinite(y[k]))
          return std::numeric_limits<double>::infinity();
        d = std::max(d, std::abs(x[k] - y[k]));
        s = std::max(s, std::abs(y[k]));
      }
    return d / s;
  }

  void
  check_dimension(const unsigned int dim)
  {
    const std::string tag = std::to_string(dim) + "D: ";
    // A chain 0-1-2 with gaps 0.005, 0.01, particle 0 at 0.004 from the
    // wall y = 0, particle 3 alone.
    const double      z  = dim == 3 ? 0.5 : 0.;
    std::vector<Vec3> X  = {{{0.3, a + 0.004, z}}};
    const auto        go = [&](const Vec3 &from, double gap, double angle) {
      const double l = 2. * a + gap;
      return Vec3{{from[0] + l * std::cos(angle),
                   from[1] + l * std::sin(angle),
                   z + (dim == 3 ? 0.3 * gap : 0.)}};
    };
    X.push_back(go(X[0], 0.005, 0.3));
    X.push_back(go(X[1], 0.01, -0.2));
    X.push_back({{0.8, 0.7, z}});
    const std::size_t         n = X.size();
    const std::vector<double> radii(n, a);
    Wall                      wall;
    wall.axis     = 1;
    wall.position = 0.;
    wall.side     = 1;
    wall.velocity = {{0.3, 0., 0.}};

    // The undisturbed shear: u* = (rate y, 0, 0), omega* = -rate / 2 e_z.
    std::vector<double> u_star(6 * n, 0.);
    std::vector<Vec3>   us(n), ws(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        u_star[6 * i]     = rate * X[i][1];
        u_star[6 * i + 5] = -0.5 * rate;
        us[i]             = {{u_star[6 * i], 0., 0.}};
        ws[i]             = {{0., 0., -0.5 * rate}};
      }

    LubricationCorrection c(settings(dim, 0.));
    c.set_walls({wall});
    c.find_bonds(X, radii);
    std::cout << tag << c.bonds().size() << " bonds" << std::endl;
    const ModelFluid fluid(c, n, dim);

    // The reference: the correction after the solve with the fluid's drag,
    // from the fluid's velocities without loads.
    const std::vector<Vec3>   none(n, Vec3{{0., 0., 0.}});
    const std::vector<double> y_free = fluid.velocities(u_star, none, none);
    std::vector<Vec3>         u_pred(n), w_pred(n), u_ref, w_ref;
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          u_pred[i][d] = y_free[6 * i + d];
          w_pred[i][d] = y_free[6 * i + 3 + d];
        }
    LubricationCorrection ref(settings(dim, fluid.zeta_f));
    ref.set_walls({wall});
    ref.correct(X, radii, u_pred, w_pred, u_ref, w_ref);
    std::vector<double> x_ref(6 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          x_ref[6 * i + d]     = u_ref[i][d];
          x_ref[6 * i + 3 + d] = w_ref[i][d];
        }

    // a. The coupling with the isolated drags, iterated plainly.
    const LubricationCoupling coupling(c, radii);
    std::vector<double>       x = y_free, step;
    std::vector<Vec3>         F, T;
    unsigned int              steps = 0;
    while (steps < 80 && relative_difference(x, x_ref) > 1e-9)
      {
        coupling.loads(x, F, T);
        std::vector<double> r = fluid.velocities(u_star, F, T);
        for (std::size_t k = 0; k < r.size(); ++k)
          r[k] -= x[k];
        coupling.step(r, step);
        for (std::size_t k = 0; k < x.size(); ++k)
          x[k] += step[k];
        ++steps;
      }
    check(tag + "the coupled iteration converges to the correction with the "
                "fluid's drag (1e-9)",
          relative_difference(x, x_ref) <= 1e-9);

    // b. The coupling's drag equal to the fluid's: one step.
    LubricationCorrection exact(settings(dim, fluid.zeta_f));
    exact.set_walls({wall});
    exact.find_bonds(X, radii);
    const LubricationCoupling one(exact, radii);
    std::vector<double>       x1 = y_free;
    one.loads(x1, F, T);
    std::vector<double> r1 = fluid.velocities(u_star, F, T);
    for (std::size_t k = 0; k < r1.size(); ++k)
      r1[k] -= x1[k];
    one.step(r1, step);
    for (std::size_t k = 0; k < x1.size(); ++k)
      x1[k] += step[k];
    check(tag + "with the fluid's own mobility one step gives it (1e-9)",
          relative_difference(x1, x_ref) <= 1e-9);

    // c. The far particle and the balance of the pair loads.
    double far = 0.;
    for (unsigned int k = 0; k < 6; ++k)
      far = std::max(far, std::abs(x[6 * 3 + k] - u_star[6 * 3 + k]));
    check(tag + "the particle without bonds keeps u* (1e-12)", far <= 1e-12);
    LubricationCorrection pairs_only(settings(dim, 0.));
    pairs_only.find_bonds(X, radii);
    LubricationCoupling(pairs_only, radii).loads(x, F, T);
    double sum = 0., largest = 0.;
    for (unsigned int d = 0; d < 3; ++d)
      {
        double s = 0.;
        for (std::size_t i = 0; i < n; ++i)
          {
            s += F[i][d];
            largest = std::max(largest, std::abs(F[i][d]));
          }
        sum = std::max(sum, std::abs(s));
      }
    check(tag + "the pair loads cancel (1e-9 of the largest)",
          largest > 0. && sum <= 1e-9 * largest);
  }
} // namespace

int
main()
{
  check_dimension(2);
  check_dimension(3);
  return TestTools::failures() != 0;
}
