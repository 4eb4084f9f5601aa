#include <algorithm>
#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/lubrication_correction.h>
#include <string>

namespace Fidus::Contact
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    double
    dot(const Vec3 &a, const Vec3 &b)
    {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }

    /// n.(v_i - v_j) of a bond for velocities stored 3 per particle; a wall
    /// does not move normally, so only v_i counts for it.
    double
    closing_speed(const LubricationBond &b, const std::vector<double> &v)
    {
      double w = 0.;
      for (unsigned int d = 0; d < 3; ++d)
        w += b.n[d] *
             (v[3 * b.i + d] -
              (b.j == LubricationBond::no_particle ? 0. : v[3 * b.j + d]));
      return w;
    }
  } // namespace



  LubricationCorrection::LubricationCorrection(
    const LubricationSettings &settings)
    : settings(settings)
    , search(settings.dimension, PairSearchMethod::cell_list)
  {
    if (settings.dimension != 2 && settings.dimension != 3)
      throw ContactError("lubrication: dimension must be 2 or 3, not " +
                         std::to_string(settings.dimension));
    if (!(settings.viscosity > 0.) || !(settings.range >= 0.) ||
        !(settings.roughness >= 0.) || !(settings.drag >= 0.))
      throw ContactError("lubrication: viscosity must be > 0 and range, "
                         "roughness and drag >= 0");
  }



  void
  LubricationCorrection::set_walls(const std::vector<Wall> &w)
  {
    walls = w;
  }



  void
  LubricationCorrection::set_periodicity(const std::array<double, 3> &periods)
  {
    search.set_periodicity(periods);
  }



  double
  LubricationCorrection::squeeze_resistance(const unsigned int dimension,
                                            const double       viscosity,
                                            const double       a1,
                                            const double       a2,
                                            const double       gap)
  {
    // Reduced radius of the two surfaces; a plane (a2 = 0) has 1/a2 = 0.
    const double R = a2 > 0. ? a1 * a2 / (a1 + a2) : a1;
    if (dimension == 3)
      return 6. * pi * viscosity * R * R / gap;
    return 3. * std::sqrt(2.) * pi * viscosity * std::pow(R / gap, 1.5);
  }



  double
  LubricationCorrection::drag(const double a) const
  {
    if (settings.drag > 0.)
      return settings.drag;
    return settings.dimension == 3 ? 6. * pi * settings.viscosity * a :
                                     4. * pi * settings.viscosity;
  }



  void
  LubricationCorrection::apply(const std::vector<double> &zeta,
                               const bool                 resolved,
                               const std::vector<double> &x,
                               std::vector<double>       &y) const
  {
    const std::size_t n = zeta.size();
    y.assign(3 * n, 0.);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        y[3 * i + d] = zeta[i] * x[3 * i + d];
    for (const LubricationBond &b : bond)
      {
        const double R = resolved ? b.r_resolved : b.r_true;
        const double w = closing_speed(b, x);
        for (unsigned int d = 0; d < 3; ++d)
          {
            y[3 * b.i + d] += R * w * b.n[d];
            if (b.j != LubricationBond::no_particle)
              y[3 * b.j + d] -= R * w * b.n[d];
          }
      }
  }



  LubricationStatistics
  LubricationCorrection::correct(const std::vector<Vec3>   &positions,
                                 const std::vector<double> &radii,
                                 const std::vector<Vec3>   &u_star,
                                 std::vector<Vec3>         &u,
                                 const double               dt)
  {
    const std::size_t  n   = positions.size();
    const unsigned int dim = settings.dimension;
    if (radii.size() != n || u_star.size() != n)
      throw ContactError("lubrication: positions, radii and velocities "
                         "differ in number");
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        if (!std::isfinite(positions[i][d]) || !std::isfinite(u_star[i][d]))
          throw ContactError("lubrication: particle " + std::to_string(i) +
                             " has a position or velocity that is not a "
                             "finite number");

    LubricationStatistics stat;
    bond.clear();
    u                = u_star;
    const double h_c = settings.range;

    // A bond is kept only where the true resistance exceeds the resolved
    // one, i.e. where the mesh misses some of the squeeze.
    const auto make_bond = [&](LubricationBond &b,
                               const double     a_small,
                               const double     a1,
                               const double     a2) {
      const double floor = settings.roughness * a_small;
      if (b.gap < floor)
        ++stat.n_rough;
      b.r_true     = squeeze_resistance(dim,
                                    settings.viscosity,
                                    a1,
                                    a2,
                                    std::max(b.gap, floor));
      b.r_resolved = settings.nothing_resolved ?
                       0. :
                       squeeze_resistance(dim, settings.viscosity, a1, a2, h_c);
      return b.r_true > b.r_resolved;
    };

    std::vector<PairSearch::Pair> pairs;
    search.find_pairs(positions, radii, h_c, pairs);
    for (const auto &[i, j] : pairs)
      {
        LubricationBond b;
        b.i          = i;
        b.j          = j;
        const Vec3 r = search.separation(positions[i], positions[j]);
        b.length     = std::sqrt(dot(r, r));
        b.gap        = b.length - radii[i] - radii[j];
        if (b.gap >= h_c || !(b.length > 0.))
          continue;
        for (unsigned int d = 0; d < 3; ++d)
          b.n[d] = r[d] / b.length;
        if (make_bond(b, std::min(radii[i], radii[j]), radii[i], radii[j]))
          {
            bond.push_back(b);
            ++stat.n_pairs;
          }
      }
    for (unsigned int w = 0; w < walls.size(); ++w)
      for (std::size_t i = 0; i < n; ++i)
        {
          const Wall     &wall = walls[w];
          LubricationBond b;
          b.i      = static_cast<std::uint32_t>(i);
          b.wall   = w;
          b.length = wall.side * (positions[i][wall.axis] - wall.position);
          b.gap    = b.length - radii[i];
          if (b.gap >= h_c)
            continue;
          b.n[wall.axis] = -wall.side;
          if (make_bond(b, radii[i], radii[i], 0.))
            {
              bond.push_back(b);
              ++stat.n_wall_pairs;
            }
        }
    if (bond.empty())
      return stat;

    // Right-hand side b = A_resolved u*, solved for A_true u = b by
    // Jacobi-preconditioned conjugate gradients (A_true is the drag plus a
    // sum of rank-one positive terms: symmetric positive definite).
    std::vector<double> zeta(n), x(3 * n), rhs, ax, r(3 * n), z(3 * n),
      p(3 * n), diag(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      {
        zeta[i] = drag(radii[i]);
        for (unsigned int d = 0; d < 3; ++d)
          {
            x[3 * i + d]    = u_star[i][d];
            diag[3 * i + d] = zeta[i];
          }
      }
    for (const LubricationBond &b : bond)
      for (unsigned int d = 0; d < 3; ++d)
        {
          diag[3 * b.i + d] += b.r_true * b.n[d] * b.n[d];
          if (b.j != LubricationBond::no_particle)
            diag[3 * b.j + d] += b.r_true * b.n[d] * b.n[d];
        }
    const std::vector<double> x_star = x;
    apply(zeta, true, x, rhs);
    apply(zeta, false, x, ax);
    double rhs_norm2 = 0., rz = 0., r_norm2 = 0.;
    for (std::size_t k = 0; k < 3 * n; ++k)
      {
        r[k] = rhs[k] - ax[k];
        z[k] = r[k] / diag[k];
        p[k] = z[k];
        rhs_norm2 += rhs[k] * rhs[k];
        rz += r[k] * z[k];
        r_norm2 += r[k] * r[k];
      }
    const double goal2 = settings.tolerance * settings.tolerance * rhs_norm2;
    unsigned int it    = 0;
    while (r_norm2 > goal2 && it < settings.max_iterations)
      {
        apply(zeta, false, p, ax);
        double pap = 0.;
        for (std::size_t k = 0; k < 3 * n; ++k)
          pap += p[k] * ax[k];
        const double alpha  = rz / pap;
        double       rz_new = 0.;
        r_norm2             = 0.;
        for (std::size_t k = 0; k < 3 * n; ++k)
          {
            x[k] += alpha * p[k];
            r[k] -= alpha * ax[k];
            z[k] = r[k] / diag[k];
            rz_new += r[k] * z[k];
            r_norm2 += r[k] * r[k];
          }
        const double beta = rz_new / rz;
        rz                = rz_new;
        for (std::size_t k = 0; k < 3 * n; ++k)
          p[k] = z[k] + beta * p[k];
        ++it;
      }
    stat.iterations = it;
    stat.residual =
      rhs_norm2 > 0. ? std::sqrt(r_norm2 / rhs_norm2) : std::sqrt(r_norm2);
    stat.converged = r_norm2 <= goal2;

    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < dim; ++d)
        u[i][d] = x[3 * i + d];

    // The normal force each bond adds, positive apart: R w - Rres w*, with
    // w = n.(u_i - u_j) the closing speed (before the step correction
    // below, which is a matter of time integration, not a force).
    for (LubricationBond &b : bond)
      b.force = b.r_true * closing_speed(b, x) -
                b.r_resolved * closing_speed(b, x_star);

    // The Euler step's tangential opening of each pair, taken off its
    // normal velocity and shared in proportion to the mobilities 1/zeta
    // (computed from the lubricated velocities of all pairs at once).
    if (dt > 0.)
      {
        std::vector<Vec3> du(n, Vec3{{0., 0., 0.}});
        for (const LubricationBond &b : bond)
          {
            if (b.j == LubricationBond::no_particle)
              continue; // a particle sliding along a plane keeps its gap
            Vec3   w{{0., 0., 0.}}, r_new{{0., 0., 0.}};
            double wn = 0.;
            for (unsigned int d = 0; d < 3; ++d)
              {
                w[d] = u[b.j][d] - u[b.i][d];
                wn += b.n[d] * w[d];
                r_new[d] = b.length * b.n[d] + dt * w[d];
              }
            const double opening =
              std::sqrt(dot(r_new, r_new)) - b.length - dt * wn;
            const double zi = zeta[b.i], zj = zeta[b.j];
            for (unsigned int d = 0; d < dim; ++d)
              {
                du[b.i][d] += opening / dt * zj / (zi + zj) * b.n[d];
                du[b.j][d] -= opening / dt * zi / (zi + zj) * b.n[d];
              }
          }
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            u[i][d] += du[i][d];
      }

    return stat;
  }
} // namespace Fidus::Contact
