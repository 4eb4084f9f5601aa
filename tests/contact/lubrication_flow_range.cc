// The lubrication correction's two resolved responses
// (LubricationSettings::flow_range, LubricationCorrection::
// set_external_forces): the mesh is modelled to resist a pair's approach
// like a gap h_f when the ambient flow closes it and like a gap h_c when a
// force pushes it. Head-on pairs of equal spheres and discs, where every
// answer is a closed form (zeta the drag, R(h) the squeeze resistance):
//
// a. Flow only: a predicted closing speed 2D / (zeta + 2 R(h_f)) (the mesh's
//    response to a drive D) becomes 2D / (zeta + 2 R(h)), 1e-12.
// b. Forces only: a pair pushed together by +-F, predicted closing speed
//    2F / (zeta + 2 R(h_c)), becomes 2F / (zeta + 2 R(h)), 1e-12, and the
//    stored bond force is what changed the velocities: zeta (u_0 - u*_0).n
//    = -force.
// c. Both at once: the sum of a and b (the correction is linear), 1e-12.
// d. A gap between h_c and h_f, forces only: the mesh resolves the forced
//    approach there, so u = u* (1e-12); with the flow it is corrected.
// e. Without external forces the flow range alone acts: the answer of a
//    single range h_f (flow_range < 0), 1e-12.
// f. A particle sliding along a wall at a gap between the walls' squeeze
//    range and their tangential range (tangential_wall_range): only the
//    tangential terms act, so the normal velocity is the predicted one
//    (1e-12) and the sliding is slowed; beyond both ranges nothing
//    changes (1e-12).
// g. The same for two particles sliding past each other at a gap between
//    the pairs' squeeze range and their tangential range (tangential_range):
//    the closing speed is the predicted one, the relative sliding is
//    slowed, and beyond both ranges nothing changes (1e-12).
// h. The flow's resolved gap as a ramp (LubricationSettings::flow_edge
//    h_o > h_f): a predicted closing speed 2D / (zeta + 2 R(g)), g = h_f +
//    (1 - h_f / h_o) h, becomes 2D / (zeta + 2 R(h)) at a gap below h_f and
//    at one between h_f and h_o (1e-12); just below h_o the change vanishes
//    with the distance to h_o (continuity), and at h_o and beyond u = u*;
//    forces between h_c and h_o keep u = u* (1e-12).

#include "test_tools.h"

#include <array>
#include <cmath>
#include <fidus/lubrication/lubrication_correction.h>
#include <iostream>
#include <string>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  constexpr double eta = 1.3, a = 0.1;

  /// The settings of every case: exact squeeze (no roughness), with the
  /// tangential terms.
  LubricationSettings
  settings(const unsigned dim,
           const double   h_c,
           const double   h_f,
           const double   h_o = -1.)
  {
    LubricationSettings s;
    s.dimension  = dim;
    s.viscosity  = eta;
    s.range      = h_c;
    s.flow_range = h_f;
    s.flow_edge  = h_o;
    s.roughness  = 0.;
    s.tangential = true;
    return s;
  }

  double
  resistance(const unsigned dim, const double gap)
  {
    return LubricationCorrection::squeeze_resistance(dim, eta, a, a, gap);
  }

  /// Closing speed n.(u_0 - u_1) after the correction of a head-on pair at
  /// gap @p h whose predicted closing speed is @p closing_star, with
  /// external forces +-@p force pushing it together; @p bond_force gets the
  /// stored normal force of the bond (0 without a bond).
  double
  corrected(const unsigned dim,
            const double   h,
            const double   h_c,
            const double   h_f,
            const double   closing_star,
            const double   force,
            double        &bond_force,
            double        &velocity_change,
            const double   h_o = -1.)
  {
    LubricationCorrection   lub(settings(dim, h_c, h_f, h_o));
    const std::vector<Vec3> x = {{{0.3, 0.4, 0.}},
                                 {{0.3 + 2 * a + h, 0.4, 0.}}};
    if (force != 0.)
      lub.set_external_forces({{{force, 0., 0.}}, {{-force, 0., 0.}}});
    const std::vector<Vec3> u_star = {{{0.5 * closing_star, 0.1, 0.}},
                                      {{-0.5 * closing_star, 0.1, 0.}}};
    std::vector<Vec3>       u;
    lub.correct(x, {a, a}, u_star, u);
    bond_force      = lub.bonds().empty() ? 0. : lub.bonds()[0].force;
    velocity_change = lub.drag(a) * (u[0][0] - u_star[0][0]);
    return u[0][0] - u[1][0];
  }



  /// The constants of every case in @p dim dimensions: a gap h below both
  /// ranges h_c < h_f, the drag, the flow's drive D and the force F, and
  /// the closing speed 2 push / (zeta + 2 R(gap)) of a head-on pair.
  struct Case
  {
    explicit Case(const unsigned int dim)
      : dim(dim)
      , D(std::to_string(dim) + "D: ")
      , zeta(dim == 3 ? 6. * M_PI * eta * a : 4. * M_PI * eta)
    {}

    double
    speed(const double push, const double gap) const
    {
      return 2. * push / (zeta + 2. * resistance(dim, gap));
    }

    const unsigned int dim;
    const std::string  D;
    const double       h = 1e-3, h_c = 0.02, h_f = 0.035;
    const double       zeta;
    const double       drive = 0.7, force = 0.4;
  };



  /// Cases a to e: the flow's and the forces' resolved responses.
  void
  check_two_responses(const Case &c)
  {
    const unsigned int dim = c.dim;
    const std::string &D   = c.D;
    const double       h = c.h, h_c = c.h_c, h_f = c.h_f;
    const double       drive = c.drive, force = c.force;
    const auto         speed = [&](const double push, const double gap) {
      return c.speed(push, gap);
    };
    double f_bond = 0., change = 0.;

    const double flow =
      corrected(dim, h, h_c, h_f, speed(drive, h_f), 0., f_bond, change);
    check(D + "a. flow: 2D / (zeta + 2 R(h_f)) becomes 2D / (zeta + 2 R(h))",
          std::abs(flow - speed(drive, h)) < 1e-12 * speed(drive, h));

    const double forced =
      corrected(dim, h, h_c, h_f, speed(force, h_c), force, f_bond, change);
    check(D + "b. forces: 2F / (zeta + 2 R(h_c)) becomes 2F / (zeta + 2 R(h)); "
              "the bond force is zeta (u - u*)",
          std::abs(forced - speed(force, h)) < 1e-12 * speed(force, h) &&
            std::abs(change + f_bond) < 1e-9 * std::abs(f_bond) && f_bond > 0.);

    const double both = corrected(dim,
                                  h,
                                  h_c,
                                  h_f,
                                  speed(drive, h_f) + speed(force, h_c),
                                  force,
                                  f_bond,
                                  change);
    check(D + "c. flow and forces: the sum of a and b",
          std::abs(both - speed(drive, h) - speed(force, h)) < 1e-12 * both);

    // Between the ranges: the forced approach is resolved, the flow's not.
    const double h_mid      = 0.5 * (h_c + h_f);
    const double forced_mid = corrected(dim,
                                        h_mid,
                                        h_c,
                                        h_f,
                                        speed(force, h_mid),
                                        force,
                                        f_bond,
                                        change);
    const double flow_mid =
      corrected(dim, h_mid, h_c, h_f, speed(drive, h_f), 0., f_bond, change);
    check(D + "d. gap between h_c and h_f: forced u = u*, flow corrected",
          std::abs(forced_mid - speed(force, h_mid)) <
              1e-12 * speed(force, h_mid) &&
            std::abs(flow_mid - speed(drive, h_mid)) <
              1e-12 * speed(drive, h_mid));

    const double single =
      corrected(dim, h, h_f, -1., speed(drive, h_f), 0., f_bond, change);
    check(D + "e. no external forces: the same as a single range h_f",
          std::abs(single - flow) < 1e-12 * flow);
  }



  /// Cases f and g: sliding between the squeeze and tangential ranges.
  void
  check_tangential_ranges(const Case &c)
  {
    const unsigned int dim = c.dim;
    const std::string &D   = c.D;
    const double       h_c = c.h_c, h_f = c.h_f, h_mid = 0.5 * (h_c + h_f);
    // f. A particle above the wall y = 0, sliding along x.
    const auto slide = [&](const double gap) {
      LubricationSettings s   = settings(dim, h_c, -1.);
      s.wall_range            = h_c;
      s.tangential_wall_range = h_f;
      LubricationCorrection lub(s);
      Wall                  wall;
      wall.axis     = 1;
      wall.position = 0.;
      wall.side     = 1;
      lub.set_walls({wall});
      const std::vector<Vec3> x      = {{{0.5, a + gap, 0.}}};
      const std::vector<Vec3> u_star = {{{0.3, -0.02, 0.}}};
      std::vector<Vec3>       u;
      lub.correct(x, {a}, u_star, u);
      return u[0];
    };
    const Vec3 between = slide(h_mid), beyond = slide(2. * h_f);
    check(D + "f. sliding between the wall's ranges: normal u = u*, "
              "sliding slowed; beyond both: u = u*",
          std::abs(between[1] + 0.02) < 1e-12 && between[0] < 0.3 &&
            between[0] > 0. && std::abs(beyond[0] - 0.3) < 1e-12 &&
            std::abs(beyond[1] + 0.02) < 1e-12);

    // g. A pair along x, closing at 0.04 and sliding along y at 0.3.
    const auto pass = [&](const double gap) {
      LubricationSettings s = settings(dim, h_c, -1.);
      s.tangential_range    = h_f;
      LubricationCorrection   lub(s);
      const std::vector<Vec3> x      = {{{0.3, 0.4, 0.}},
                                        {{0.3 + 2 * a + gap, 0.4, 0.}}};
      const std::vector<Vec3> u_star = {{{0.02, 0.15, 0.}},
                                        {{-0.02, -0.15, 0.}}};
      std::vector<Vec3>       u;
      lub.correct(x, {a, a}, u_star, u);
      return std::array<double, 2>{{u[0][0] - u[1][0], u[0][1] - u[1][1]}};
    };
    const auto pass_between = pass(h_mid), pass_beyond = pass(2. * h_f);
    check(D + "g. pair sliding between its ranges: closing u = u*, "
              "sliding slowed; beyond both: u = u*",
          std::abs(pass_between[0] - 0.04) < 1e-12 && pass_between[1] < 0.3 &&
            pass_between[1] > 0. && std::abs(pass_beyond[0] - 0.04) < 1e-12 &&
            std::abs(pass_beyond[1] - 0.3) < 1e-12);
  }



  /// Case h: the flow's resolved gap as a ramp to the edge h_o.
  void
  check_flow_ramp(const Case &c)
  {
    const unsigned int dim = c.dim;
    const std::string &D   = c.D;
    const double       h = c.h, h_c = c.h_c, h_f = c.h_f, zeta = c.zeta;
    const double       drive = c.drive, force = c.force;
    const auto         speed = [&](const double push, const double gap) {
      return c.speed(push, gap);
    };
    double f_bond = 0., change = 0.;
    // h. The ramp from h_f at contact to the true gap at h_o.
    const double h_o  = 2. * h_f;
    const auto   ramp = [&](const double gap) {
      return gap < h_o ? h_f + (1. - h_f / h_o) * gap : gap;
    };
    bool ramp_ok = true;
    for (const double gap : {h, 0.5 * (h_f + h_o)})
      {
        const double v = corrected(dim,
                                   gap,
                                   h_c,
                                   h_f,
                                   speed(drive, ramp(gap)),
                                   0.,
                                   f_bond,
                                   change,
                                   h_o);
        ramp_ok &= std::abs(v - speed(drive, gap)) < 1e-12 * speed(drive, gap);
      }
    double       change_near = 0., change_at = 0.;
    const double near = h_o * (1. - 1e-6);
    corrected(dim,
              near,
              h_c,
              h_f,
              speed(drive, near),
              0.,
              f_bond,
              change_near,
              h_o);
    corrected(dim,
              h_o,
              h_c,
              h_f,
              speed(drive, h_o),
              0.,
              f_bond,
              change_at,
              h_o);
    const double forced_edge = corrected(dim,
                                         0.5 * (h_f + h_o),
                                         h_c,
                                         h_f,
                                         speed(force, 0.5 * (h_f + h_o)),
                                         force,
                                         f_bond,
                                         change,
                                         h_o);
    check(D + "h. flow ramp h_f -> h_o: 2D / (zeta + 2 R(g)) becomes "
              "2D / (zeta + 2 R(h)) below and above h_f; continuous at "
              "h_o; forces between h_c and h_o: u = u*",
          ramp_ok && std::abs(change_near) < 1e-5 * zeta * speed(drive, near) &&
            change_at == 0. &&
            std::abs(forced_edge - speed(force, 0.5 * (h_f + h_o))) <
              1e-12 * speed(force, h_o));
  }
} // namespace

int
main()
{
  for (const unsigned dim : {2u, 3u})
    {
      const Case c(dim);
      check_two_responses(c);
      check_tangential_ranges(c);
      check_flow_ramp(c);
    }
  return 0;
}
