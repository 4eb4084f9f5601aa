#include "bond_algebra.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/vector_operations.h>
#include <fidus/lubrication/lubrication_correction.h>
#include <fidus/lubrication/step_mean_resistance.h>
#include <string>

namespace Fidus::Contact
{
  using BondAlgebra::gather;
  using BondAlgebra::is_wall;
  using BondAlgebra::Local;
  using BondAlgebra::scatter_add;

  namespace
  {
    constexpr double pi = 3.14159265358979323846;


    Vec3
    part(const Local &l, const unsigned int k)
    {
      return {{l[3 * k], l[3 * k + 1], l[3 * k + 2]}};
    }

    void
    add_part(Local &l, const unsigned int k, const Vec3 &v, const double s)
    {
      for (unsigned int d = 0; d < 3; ++d)
        l[3 * k + d] += s * v[d];
    }

    /// n.(U_i - U_j) of a bond; a wall does not move normally.
    double
    closing_speed(const LubricationBond &b, const Local &v)
    {
      return dot(b.n, part(v, 0)) - dot(b.n, part(v, 2));
    }

    /// Loads (forces and torques on i and j) of the normal squeeze of
    /// resistance R.
    Local
    normal_loads(const LubricationBond &b, const double R, const Local &v)
    {
      Local        f{};
      const double w = closing_speed(b, v);
      add_part(f, 0, b.n, -R * w);
      add_part(f, 2, b.n, R * w);
      return f;
    }

    /**
     * Loads of the tangential lubrication of coefficient c (class
     * documentation of LubricationCorrection), for the generalised
     * velocities v; a wall moves with b.wall_velocity when @p wall_motion,
     * else it is at rest (the loads are then linear in v).
     */
    Local
    loads_of_sliding(const LubricationBond &b,
                     const double           c,
                     const unsigned int     dimension,
                     const Local           &v,
                     const bool             wall_motion)
    {
      const bool   wall  = is_wall(b);
      const double kappa = dimension == 3 ? 0.6 : 1.;
      const Vec3   Ui = part(v, 0), wi = part(v, 1);
      const Vec3   Uj =
        wall ? (wall_motion ? b.wall_velocity : Vec3{}) : part(v, 2);
      const Vec3   wj    = wall ? Vec3{} : part(v, 3);
      const double R     = wall ? b.a_i : b.a_i * b.a_j / (b.a_i + b.a_j);
      const double delta = wall ? -1. : (b.a_i - b.a_j) / (b.a_i + b.a_j);
      Vec3         ai_n, aj_n;
      for (unsigned int d = 0; d < 3; ++d)
        {
          ai_n[d] = b.a_i * b.n[d];
          aj_n[d] = b.a_j * b.n[d];
        }
      const Vec3 si = cross(wi, ai_n), sj = cross(wj, aj_n);
      Vec3       dU, S;
      for (unsigned int d = 0; d < 3; ++d)
        {
          const double s_i = Ui[d] + si[d], s_j = Uj[d] - sj[d];
          // The gap's profile moves with the particles: a plane sliding
          // along itself does not change it.
          const double profile = Ui[d] / b.a_i + (wall ? 0. : Uj[d] / b.a_j);
          dU[d]                = s_j - s_i;
          S[d]                 = s_i + s_j - 2. * R * profile;
        }
      const double dUn = dot(dU, b.n), Sn = dot(S, b.n);
      Vec3         f_j, shear_i, shear_j;
      for (unsigned int d = 0; d < 3; ++d)
        {
          dU[d] -= dUn * b.n[d];
          S[d] -= Sn * b.n[d];
          f_j[d]     = -c * (dU[d] - kappa * delta * S[d]);
          shear_i[d] = c * (dU[d] - kappa * S[d]);
          shear_j[d] = -c * (dU[d] + kappa * S[d]);
        }
      Local f{};
      add_part(f, 0, f_j, -1.);
      add_part(f, 1, cross(ai_n, shear_i), 1.);
      if (!wall)
        {
          add_part(f, 2, f_j, 1.);
          add_part(f, 3, cross(aj_n, shear_j), -1.);
        }
      return f;
    }
    /// Keep the tangential loads @p f of bond @p b on it: the force on j,
    /// or on the wall (the opposite of the one on i), and the torques.
    void
    record_sliding_loads(LubricationBond &b, const Local &f)
    {
      for (unsigned int d = 0; d < 3; ++d)
        b.tangential_force[d] = -f[d];
      b.torque_i = part(f, 1);
      b.torque_j = part(f, 3);
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
  LubricationCorrection::set_wall_velocity(
    std::function<Vec3(const Wall &, const Vec3 &)> velocity)
  {
    wall_velocity_at = std::move(velocity);
  }



  void
  LubricationCorrection::set_periodicity(const std::array<double, 3> &periods)
  {
    search.set_periodicity(periods);
  }



  void
  LubricationCorrection::set_external_forces(const std::vector<Vec3> &forces)
  {
    external_force = forces;
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
      {
        // The logarithmic term, next to the leading one, matters at the
        // gaps the mesh hands over (a few tenths of a cell): without it a
        // pair of equal spheres is 20 % too mobile at h = 0.1a.
        const double b = a2 > 0. ? a2 / a1 : 0.;
        const double g =
          a2 > 0. ? b * (1. + 7. * b + b * b) / (5. * std::pow(1. + b, 3)) :
                    0.2;
        const double xi = a2 > 0. ? 2. * gap / (a1 + a2) : gap / a1;
        return 6. * pi * viscosity *
               (R * R / gap + a1 * g * std::max(0., std::log(1. / xi)));
      }
    return 3. * std::sqrt(2.) * pi * viscosity * std::pow(R / gap, 1.5);
  }



  double
  LubricationCorrection::tangential_resistance(const unsigned int dimension,
                                               const double       viscosity,
                                               const double       a1,
                                               const double       a2,
                                               const double       gap,
                                               const double       range)
  {
    const double R = a2 > 0. ? a1 * a2 / (a1 + a2) : a1;
    if (dimension == 3)
      return 2. * pi * viscosity * R *
             std::max(0., std::log(std::max(R, range) / gap));
    return pi * viscosity * std::sqrt(2. * R / gap);
  }



  std::array<double, 12>
  LubricationCorrection::tangential_loads(const LubricationBond &b,
                                          const double           c,
                                          const unsigned int     dimension,
                                          const std::array<double, 12> &v)
  {
    return loads_of_sliding(b, c, dimension, v, true);
  }



  double
  LubricationCorrection::drag(const double a) const
  {
    if (settings.drag > 0.)
      return settings.drag;
    return settings.dimension == 3 ? 6. * pi * settings.viscosity * a :
                                     4. * pi * settings.viscosity;
  }



  double
  LubricationCorrection::rotational_drag(const double a) const
  {
    if (settings.drag > 0.)
      return settings.drag * a * a * (settings.dimension == 3 ? 4. / 3. : 1.);
    return settings.dimension == 3 ? 8. * pi * settings.viscosity * a * a * a :
                                     4. * pi * settings.viscosity * a * a;
  }



  std::array<double, 2>
  LubricationCorrection::resistances(const LubricationBond &b,
                                     const Resistance       resistance)
  {
    // The two resolved responses differ in the normal squeeze only.
    switch (resistance)
      {
        case Resistance::true_gap:
          return {{b.r_true, b.t_true}};
        case Resistance::resolved:
          return {{b.r_resolved, b.t_resolved}};
        default:
          return {{b.r_resolved_force, b.t_resolved}};
      }
  }



  void
  LubricationCorrection::apply(const std::vector<double> &zeta,
                               const std::vector<double> &zeta_rot,
                               const Resistance           resistance,
                               const std::vector<double> &x,
                               std::vector<double>       &y) const
  {
    const std::size_t n = zeta.size();
    y.assign(6 * n, 0.);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          y[6 * i + d]     = zeta[i] * x[6 * i + d];
          y[6 * i + 3 + d] = zeta_rot[i] * x[6 * i + 3 + d];
        }
    for (const LubricationBond &b : bond)
      {
        const Local v                       = gather(b, x);
        const auto [r_normal, c_tangential] = resistances(b, resistance);
        scatter_add(b, normal_loads(b, r_normal, v), -1., y);
        if (settings.tangential)
          scatter_add(
            b,
            loads_of_sliding(b, c_tangential, settings.dimension, v, false),
            -1.,
            y);
      }
  }



  void
  LubricationCorrection::solve(const std::vector<double> &zeta,
                               const std::vector<double> &zeta_rot,
                               const Resistance           resistance,
                               const std::vector<double> &rhs,
                               std::vector<double>       &x,
                               LubricationStatistics     &stat) const
  {
    const std::size_t   n = zeta.size();
    std::vector<double> diag(6 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          diag[6 * i + d]     = zeta[i];
          diag[6 * i + 3 + d] = zeta_rot[i];
        }
    // The exact diagonal of the bond terms, one local unit vector at a time.
    for (const LubricationBond &b : bond)
      {
        const auto [R, c] = resistances(b, resistance);
        for (unsigned int k = 0; k < (is_wall(b) ? 6u : 12u); ++k)
          {
            Local e{};
            e[k]          = 1.;
            const Local f = normal_loads(b, R, e);
            double      t = 0.;
            if (settings.tangential)
              t = loads_of_sliding(b, c, settings.dimension, e, false)[k];
            diag[6 * (k < 6 ? b.i : b.j) + k % 6] -= f[k] + t;
          }
      }
    const BondAlgebra::CgResult cg = BondAlgebra::jacobi_cg(
      [&](const std::vector<double> &v, std::vector<double> &y) {
        apply(zeta, zeta_rot, resistance, v, y);
      },
      diag,
      rhs,
      settings.tolerance,
      settings.max_iterations,
      x);
    stat.iterations = cg.iterations;
    stat.residual   = cg.rhs2 > 0. ? std::sqrt(cg.residual2 / cg.rhs2) :
                                     std::sqrt(cg.residual2);
    stat.converged =
      cg.residual2 <= settings.tolerance * settings.tolerance * cg.rhs2;
  }



  double
  LubricationCorrection::approach_speed(const LubricationBond   &b,
                                        const std::vector<Vec3> &u)
  {
    double s = 0.;
    for (unsigned int d = 0; d < 3; ++d)
      s += b.n[d] * (u[b.i][d] - (is_wall(b) ? 0. : u[b.j][d]));
    return s;
  }



  double
  LubricationCorrection::length_after_step(const LubricationBond   &b,
                                           const std::vector<Vec3> &u,
                                           const double             dt)
  {
    if (is_wall(b))
      return b.length - dt * approach_speed(b, u);
    Vec3 r_new{{0., 0., 0.}};
    for (unsigned int d = 0; d < 3; ++d)
      r_new[d] = b.length * b.n[d] + dt * (u[b.j][d] - u[b.i][d]);
    return std::sqrt(dot(r_new, r_new));
  }



  LubricationStatistics
  LubricationCorrection::correct(const std::vector<Vec3>   &positions,
                                 const std::vector<double> &radii,
                                 const std::vector<Vec3>   &u_star,
                                 std::vector<Vec3>         &u,
                                 const double               dt)
  {
    const std::vector<Vec3> w_star(u_star.size(), Vec3{{0., 0., 0.}});
    std::vector<Vec3>       w;
    return correct(positions, radii, u_star, w_star, u, w, dt);
  }



  const std::vector<LubricationBond> &
  LubricationCorrection::find_bonds(const std::vector<Vec3>   &positions,
                                    const std::vector<double> &radii,
                                    const std::vector<double> &fluid_radii)
  {
    found = LubricationStatistics();
    bond.clear();
    collect_bonds(positions, radii, found, fluid_radii);
    return bond;
  }



  std::array<double, 12>
  LubricationCorrection::subgrid_loads(const LubricationBond        &b,
                                       const std::array<double, 12> &v,
                                       const bool wall_motion) const
  {
    // Both resistances are linear in their coefficient, so the difference
    // of the true and the resolved loads is the load of the difference.
    Local f = normal_loads(b, b.r_true - b.r_resolved, v);
    if (settings.tangential)
      {
        const Local t = loads_of_sliding(b,
                                         b.t_true - b.t_resolved,
                                         settings.dimension,
                                         v,
                                         wall_motion);
        for (unsigned int k = 0; k < 12; ++k)
          f[k] += t[k];
      }
    return f;
  }



  std::array<double, 12>
  LubricationCorrection::resolved_loads(const LubricationBond        &b,
                                        const std::array<double, 12> &v) const
  {
    Local f = normal_loads(b, b.r_resolved_force, v);
    if (settings.tangential)
      {
        const Local t =
          loads_of_sliding(b, b.t_resolved, settings.dimension, v, false);
        for (unsigned int k = 0; k < 12; ++k)
          f[k] += t[k];
      }
    return f;
  }



  LubricationStatistics
  LubricationCorrection::measure(const std::vector<Vec3> &u,
                                 const std::vector<Vec3> &w)
  {
    std::vector<double> x(6 * u.size(), 0.);
    for (std::size_t i = 0; i < u.size(); ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          x[6 * i + d]     = u[i][d];
          x[6 * i + 3 + d] = i < w.size() ? w[i][d] : 0.;
        }
    for (LubricationBond &b : bond)
      {
        const Local v = gather(b, x);
        b.force       = (b.r_true - b.r_resolved) * closing_speed(b, v);
        if (!settings.tangential)
          continue;
        const Local f = loads_of_sliding(b,
                                         b.t_true - b.t_resolved,
                                         settings.dimension,
                                         v,
                                         true);
        record_sliding_loads(b, f);
      }
    return found;
  }



  namespace
  {
    /// Throws ContactError unless the particle arrays agree in size and hold
    /// finite numbers only.
    void
    check_particle_data(const std::vector<Vec3>   &positions,
                        const std::vector<double> &radii,
                        const std::vector<Vec3>   &u_star,
                        const std::vector<Vec3>   &w_star)
    {
      const std::size_t n = positions.size();
      if (radii.size() != n || u_star.size() != n || w_star.size() != n)
        throw ContactError("lubrication: positions, radii and velocities "
                           "differ in number");
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          if (!std::isfinite(positions[i][d]) || !std::isfinite(u_star[i][d]) ||
              !std::isfinite(w_star[i][d]))
            throw ContactError("lubrication: particle " + std::to_string(i) +
                               " has a position or velocity that is not a "
                               "finite number");
    }
  } // namespace



  /// The solution of the corrected system and what the bond loads and the
  /// step correction need from its set-up.
  struct LubricationCorrection::CorrectedSystem
  {
    /// The drag of each particle.
    std::vector<double> zeta;
    /// The corrected generalised velocities (6 per particle).
    std::vector<double> x;
    /// The predicted generalised velocities u*, w*.
    std::vector<double> x_star;
    /// The part of u* driven by the external forces; empty if not used.
    std::vector<double> x_force;
    /// The rotational drags and the right-hand side of the true system.
    std::vector<double> zeta_rot, rhs;
  };



  bool
  LubricationCorrection::fill_resistances(
    LubricationBond             &b,
    const double                 a_small,
    const double                 range,
    const double                 flow_range,
    const double                 flow_edge,
    const double                 tangential_range,
    LubricationStatistics       &stat,
    const std::array<double, 2> &resolved_radii) const
  {
    // A bond is kept only where the true resistance exceeds a resolved
    // one, i.e. where the mesh misses some of the squeeze. A wall gets the
    // same resolved resistance in both responses.
    const unsigned int dim   = settings.dimension;
    const double       floor = settings.roughness * a_small;
    if (b.gap < floor)
      ++stat.n_rough;
    const double gap      = std::max(b.gap, floor);
    const double ra_i     = resolved_radii[0] >= 0. ? resolved_radii[0] : b.a_i;
    const double ra_j     = resolved_radii[1] >= 0. ? resolved_radii[1] : b.a_j;
    const auto   resolved = [&](const double r) {
      return settings.nothing_resolved ? 0. :
                                           squeeze_resistance(dim,
                                                            settings.viscosity,
                                                            ra_i,
                                                            ra_j,
                                                            std::max(gap, r));
    };
    b.r_true = squeeze_resistance(dim, settings.viscosity, b.a_i, b.a_j, gap);
    // The flow's resolved gap: a step at h_f, or the ramp from h_f at
    // contact to the true gap at the edge h_o.
    const double flow_gap = flow_edge > flow_range && gap < flow_edge ?
                              flow_range + (1. - flow_range / flow_edge) * gap :
                              flow_range;
    b.r_resolved          = resolved(flow_gap);
    b.r_resolved_force    = resolved(range);
    if (settings.tangential)
      {
        b.t_true     = tangential_resistance(dim,
                                         settings.viscosity,
                                         b.a_i,
                                         b.a_j,
                                         gap,
                                         tangential_range);
        b.t_resolved = settings.nothing_resolved ?
                         0. :
                         tangential_resistance(dim,
                                               settings.viscosity,
                                               ra_i,
                                               ra_j,
                                               std::max(gap, tangential_range),
                                               tangential_range);
      }
    return b.r_true > std::min(b.r_resolved, b.r_resolved_force) ||
           (settings.tangential && b.t_true > b.t_resolved);
  }



  void
  LubricationCorrection::collect_bonds(const std::vector<Vec3>   &positions,
                                       const std::vector<double> &radii,
                                       LubricationStatistics     &stat,
                                       const std::vector<double> &fluid_radii)
  {
    const std::size_t n   = positions.size();
    const double      h_c = settings.range;
    const double      h_f =
      settings.flow_range >= 0. ? settings.flow_range : settings.range;
    const double h_o = std::max(h_f, settings.flow_edge);
    const double h_w =
      settings.wall_range >= 0. ? settings.wall_range : settings.range;
    const double h_t =
      settings.tangential_range >= 0. ? settings.tangential_range : h_c;
    const double h_wt = settings.tangential_wall_range >= 0. ?
                          settings.tangential_wall_range :
                          h_w;

    // With a resolved gap fraction every range is that fraction of the
    // bond's smaller radius (the radius for a wall), so the pair search
    // reaches out to it for the largest radius. A particle the fluid saw
    // shrunk (fluid_radii) has every gap of its widened by as much, and the
    // fluid resolves each at its widened width: a gap below half the smaller
    // radius is corrected from there, where the gap formulas still hold (a
    // wider one's difference is a few per cent of the drag, and the formulas no
    // longer apply).
    const double fraction = settings.resolved_gap_fraction;
    const double a_max =
      radii.empty() ? 0. : *std::max_element(radii.begin(), radii.end());
    const bool   shrunk = fraction > 0. && fluid_radii.size() == radii.size();
    const double widened_reach = 0.5;
    const double h_pairs =
      fraction > 0. ?
        (shrunk ? std::max(fraction, widened_reach) : fraction) * a_max :
        std::max(std::max(h_c, h_o), settings.tangential ? h_t : 0.);
    // The gap a bond is resolved at: its fluid width if the shrinking
    // widened it and it is within reach, else the resolved fraction.
    const auto resolved_gap = [&](const double length,
                                  const double gap,
                                  const double a_small,
                                  const double fluid_radii_sum) {
      return shrunk && gap < widened_reach * a_small ?
               std::max(fraction * a_small, length - fluid_radii_sum) :
               fraction * a_small;
    };
    std::vector<PairSearch::Pair> pairs;
    search.find_pairs(positions, radii, h_pairs, pairs);
    for (const auto &[i, j] : pairs)
      {
        LubricationBond b;
        b.i                  = i;
        b.j                  = j;
        b.a_i                = radii[i];
        b.a_j                = radii[j];
        const Vec3 r         = search.separation(positions[i], positions[j]);
        b.length             = std::sqrt(dot(r, r));
        b.gap                = b.length - radii[i] - radii[j];
        const double a_small = std::min(radii[i], radii[j]);
        const double h_bond =
          resolved_gap(b.length,
                       b.gap,
                       a_small,
                       shrunk ? fluid_radii[i] + fluid_radii[j] : 0.);
        if (b.gap >= (fraction > 0. ? h_bond : h_pairs) || !(b.length > 0.))
          continue;
        for (unsigned int d = 0; d < 3; ++d)
          b.n[d] = r[d] / b.length;
        if (fraction > 0. ?
              fill_resistances(b,
                               a_small,
                               h_bond,
                               h_bond,
                               0.,
                               h_bond,
                               stat,
                               {{shrunk ? fluid_radii[i] : -1.,
                                 shrunk ? fluid_radii[j] : -1.}}) :
              fill_resistances(b, a_small, h_c, h_f, h_o, h_t, stat))
          {
            bond.push_back(b);
            ++stat.n_pairs;
          }
      }
    for (unsigned int k = 0; k < walls.size(); ++k)
      for (std::size_t i = 0; i < n; ++i)
        {
          const Wall     &wall = walls[k];
          LubricationBond b;
          b.i      = static_cast<std::uint32_t>(i);
          b.wall   = k;
          b.a_i    = radii[i];
          b.length = wall.side * (positions[i][wall.axis] - wall.position);
          b.gap    = b.length - radii[i];
          const double h_bond = resolved_gap(b.length,
                                             b.gap,
                                             radii[i],
                                             shrunk ? fluid_radii[i] : 0.);
          if (b.gap >= (fraction > 0. ? h_bond : std::max(h_w, h_wt)))
            continue;
          b.n[wall.axis] = -wall.side;
          // The wall's velocity at the foot of the particle's normal.
          Vec3 foot       = positions[i];
          foot[wall.axis] = wall.position;
          b.wall_velocity =
            wall_velocity_at ? wall_velocity_at(wall, foot) : wall.velocity;
          b.wall_velocity[wall.axis] = 0.;
          if (fraction > 0. ?
                fill_resistances(b,
                                 radii[i],
                                 h_bond,
                                 h_bond,
                                 0.,
                                 h_bond,
                                 stat,
                                 {{shrunk ? fluid_radii[i] : -1., 0.}}) :
                fill_resistances(b, radii[i], h_w, h_w, 0., h_wt, stat))
            {
              bond.push_back(b);
              ++stat.n_wall_pairs;
            }
        }
  }



  std::vector<double>
  LubricationCorrection::subtract_force_response(
    const std::vector<double> &zeta,
    const std::vector<double> &zeta_rot,
    std::vector<double>       &rhs,
    LubricationStatistics     &stat) const
  {
    const std::size_t  n   = zeta.size();
    const unsigned int dim = settings.dimension;

    // The part of u* that the external forces drive, as the mesh is
    // modelled to move under them (resolved resistance R(h_c)), and the
    // difference between the two resolved resistances on it.
    std::vector<double> x_force;
    bool                two_responses = false;
    for (const LubricationBond &b : bond)
      two_responses |= b.r_resolved_force != b.r_resolved;
    if (two_responses && external_force.size() == n)
      {
        std::vector<double> f(6 * n, 0.);
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            f[6 * i + d] = external_force[i][d];
        x_force.assign(6 * n, 0.);
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            x_force[6 * i + d] = f[6 * i + d] / zeta[i];
        LubricationStatistics force_stat;
        solve(zeta,
              zeta_rot,
              Resistance::resolved_force,
              f,
              x_force,
              force_stat);
        stat.converged &= force_stat.converged;
        for (const LubricationBond &b : bond)
          scatter_add(b,
                      normal_loads(b,
                                   b.r_resolved_force - b.r_resolved,
                                   gather(b, x_force)),
                      -1.,
                      rhs);
      }
    return x_force;
  }



  LubricationCorrection::CorrectedSystem
  LubricationCorrection::solve_corrected_system(
    const std::vector<double> &radii,
    const std::vector<Vec3>   &u_star,
    const std::vector<Vec3>   &w_star,
    LubricationStatistics     &stat) const
  {
    const std::size_t  n   = radii.size();
    const unsigned int dim = settings.dimension;
    CorrectedSystem    s;

    // Right-hand side b = A_resolved u* + (the forcing of moving walls,
    // true minus resolved) + (the external forces' part, below), solved for
    // A_true u = b by Jacobi-preconditioned conjugate gradients (A_true is
    // the drag plus a sum of positive semi-definite bond terms: symmetric
    // positive definite).
    std::vector<double> &zeta = s.zeta, &x = s.x, &zeta_rot = s.zeta_rot,
                        &rhs = s.rhs;
    zeta_rot.resize(n);
    zeta.resize(n);
    x.resize(6 * n);
    for (std::size_t i = 0; i < n; ++i)
      {
        zeta[i]     = drag(radii[i]);
        zeta_rot[i] = rotational_drag(radii[i]);
        for (unsigned int d = 0; d < 3; ++d)
          {
            x[6 * i + d]     = u_star[i][d];
            x[6 * i + 3 + d] = w_star[i][d];
          }
      }
    s.x_star = x;
    apply(zeta, zeta_rot, Resistance::resolved, x, rhs);
    const auto wall_forcing = [&](const LubricationBond &b, const bool res) {
      return loads_of_sliding(b,
                              res ? b.t_resolved : b.t_true,
                              dim,
                              Local{},
                              true);
    };
    if (settings.tangential)
      for (const LubricationBond &b : bond)
        if (is_wall(b))
          {
            scatter_add(b, wall_forcing(b, false), 1., rhs);
            scatter_add(b, wall_forcing(b, true), -1., rhs);
          }

    s.x_force = subtract_force_response(zeta, zeta_rot, rhs, stat);
    const bool forces_converged = stat.converged;
    solve(zeta, zeta_rot, Resistance::true_gap, rhs, x, stat);
    stat.converged &= forces_converged;
    return s;
  }



  void
  LubricationCorrection::compute_bond_loads(const CorrectedSystem &s)
  {
    const unsigned int dim = settings.dimension;

    // The loads each bond adds: the true resistance on the corrected
    // velocities minus the resolved one on the predicted velocities. The
    // normal force is positive apart, R w - Rres w*, with w = n.(u_i - u_j)
    // the closing speed (before the step correction below, which is a
    // matter of time integration, not a force).
    for (LubricationBond &b : bond)
      {
        const Local v = gather(b, s.x), v_star = gather(b, s.x_star);
        b.force = b.r_true * closing_speed(b, v) -
                  b.r_resolved * closing_speed(b, v_star);
        if (!s.x_force.empty())
          b.force -= (b.r_resolved_force - b.r_resolved) *
                     closing_speed(b, gather(b, s.x_force));
        if (!settings.tangential)
          continue;
        Local       f = loads_of_sliding(b, b.t_true, dim, v, true);
        const Local f_res =
          loads_of_sliding(b, b.t_resolved, dim, v_star, true);
        for (unsigned int k = 0; k < 12; ++k)
          f[k] -= f_res[k];
        record_sliding_loads(b, f);
      }
  }



  void
  LubricationCorrection::average_over_step(CorrectedSystem       &s,
                                           const double           dt,
                                           LubricationStatistics &stat)
  {
    StepMeanResistance    mean(bond,
                            settings.dimension,
                            settings.viscosity,
                            settings.roughness,
                            settings.gap_in_time == GapInTime::closing_mean);
    LubricationStatistics inner;
    for (unsigned int pass = 0; pass < 30; ++pass)
      {
        for (std::size_t k = 0; k < bond.size(); ++k)
          {
            LubricationBond &b = bond[k];
            b.r_true =
              mean.next_resistance(k,
                                   b,
                                   b.gap -
                                     dt * closing_speed(b, gather(b, s.x)));
          }
        solve(s.zeta, s.zeta_rot, Resistance::true_gap, s.rhs, s.x, inner);
        stat.converged &= inner.converged;
        if (mean.take_largest_change() < 1e-3)
          break;
      }
  }



  void
  LubricationCorrection::add_step_opening(const std::vector<double> &zeta,
                                          const double               dt,
                                          std::vector<Vec3>         &u) const
  {
    const std::size_t  n   = u.size();
    const unsigned int dim = settings.dimension;

    // The Euler step's tangential opening of each pair, taken off its
    // normal velocity and shared in proportion to the mobilities 1/zeta
    // (computed from the lubricated velocities of all pairs at once).
    std::vector<Vec3> du(n, Vec3{{0., 0., 0.}});
    for (const LubricationBond &b : bond)
      {
        if (b.j == LubricationBond::no_particle)
          continue; // a particle sliding along a plane keeps its gap
        const double wn      = -approach_speed(b, u);
        const double opening = length_after_step(b, u, dt) - b.length - dt * wn;
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



  LubricationStatistics
  LubricationCorrection::correct(const std::vector<Vec3>   &positions,
                                 const std::vector<double> &radii,
                                 const std::vector<Vec3>   &u_star,
                                 const std::vector<Vec3>   &w_star,
                                 std::vector<Vec3>         &u,
                                 std::vector<Vec3>         &w,
                                 const double               dt)
  {
    const std::size_t  n   = positions.size();
    const unsigned int dim = settings.dimension;
    check_particle_data(positions, radii, u_star, w_star);

    LubricationStatistics stat;
    bond.clear();
    u = u_star;
    w = w_star;

    collect_bonds(positions, radii, stat);
    if (bond.empty())
      return stat;

    CorrectedSystem s = solve_corrected_system(radii, u_star, w_star, stat);
    if (dt > 0. && settings.gap_in_time != GapInTime::start)
      average_over_step(s, dt, stat);

    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int d = 0; d < dim; ++d)
        u[i][d] = s.x[6 * i + d];
    if (settings.tangential)
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned int d = (dim == 3 ? 0 : 2); d < 3; ++d)
          w[i][d] = s.x[6 * i + 3 + d];

    compute_bond_loads(s);

    if (dt > 0.)
      add_step_opening(s.zeta, dt, u);

    return stat;
  }
} // namespace Fidus::Contact
