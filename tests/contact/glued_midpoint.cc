// Glued pairs with their normals at the middle of the step
// (ContactProjector::project with glued_normal_positions, used by the
// trapezoidal time scheme). Two touching particles, glued, turn about each
// other with relative velocity w normal to their separation d:
//   - with the normals of the start of the step, the equality of the glued
//     row lets them move along the chord: the distance after the step is
//     sqrt(|d|^2 + dt^2 |w|^2), a gap that opens by O(dt^2);
//   - with the normal along the line of centres at the middle of the step,
//     found by repeating the projection with the middle the last one
//     reached, the distance stays |d| to round-off (|d + w dt| = |d| when
//     (d + w dt / 2).w = 0).
// Rows that are not glued keep the normals of the start of the step: an
// inelastic projection gives the same velocities with and without the
// middle positions. A middle with the wrong number of entries is refused.
// 2D and 3D.

#include "test_tools.h"

#include <cmath>
#include <fidus/contact/contact_projector.h>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  double
  distance_after(const std::vector<Vec3> &x,
                 const std::vector<Vec3> &u,
                 const double             dt)
  {
    double r2 = 0.;
    for (unsigned d = 0; d < 3; ++d)
      {
        const double s = (x[1][d] + dt * u[1][d]) - (x[0][d] + dt * u[0][d]);
        r2 += s * s;
      }
    return std::sqrt(r2);
  }

  void
  run(const unsigned dim)
  {
    const std::string tag = dim == 2 ? "2D: " : "3D: ";
    const double      a = 0.1, dt = 0.05;
    Settings          settings;
    settings.dimension              = dim;
    settings.model                  = Model::gluey;
    const double              z     = dim == 3 ? 0.5 : 0.;
    const std::vector<Vec3>   x     = {{{0.4, 0.5, z}}, {{0.6, 0.5, z}}};
    const std::vector<double> radii = {a, a};

    // Glue the touching pair: pushed together, the contact blocks it and
    // stores the blocked displacement, 2 x 10 x 0.01 = 0.2, in the glue.
    // Keeping the distance while turning then pulls (a negative
    // multiplier), which pays back about dt^2 |w|^2 / |d| = 0.025 of it.
    ContactProjector  glued(settings);
    std::vector<Vec3> u;
    glued.project(x, radii, {{{10., 0., 0.}}, {{-10., 0., 0.}}}, 0.01, u);
    check(tag + "the pushed pair is glued", glued.n_glued() == 1);
    const std::vector<GlueState::Entry> glue = glued.glue_state().entries();

    // Then the flow turns it: w = u_1 - u_0 normal to d (and out of the
    // plane as well in 3D).
    const double            wz   = dim == 3 ? 0.4 : 0.;
    const std::vector<Vec3> turn = {{{0., -1., -wz}}, {{0., 1., wz}}};
    double                  w2   = 4.;
    if (dim == 3)
      w2 += 4. * wz * wz;

    ContactProjector start_normals(settings);
    start_normals.restore_glue(glue);
    start_normals.project(x, radii, turn, dt, u);
    const double chord = std::sqrt(0.04 + dt * dt * w2);
    check(tag + "start normals: the pair moves along the chord, distance "
                "sqrt(|d|^2 + dt^2 |w|^2) to 1e-12",
          std::abs(distance_after(x, u, dt) - chord) < 1e-12);

    ContactProjector  middle(settings);
    std::vector<Vec3> mid         = x;
    unsigned int      repetitions = 0;
    for (double change = 1.; change > 1e-15 && repetitions < 30; ++repetitions)
      {
        middle.restore_glue(glue);
        middle.project(x, radii, turn, dt, u, mid);
        change = 0.;
        for (unsigned i = 0; i < 2; ++i)
          for (unsigned d = 0; d < dim; ++d)
            {
              const double m = x[i][d] + 0.5 * dt * u[i][d];
              change         = std::max(change, std::abs(m - mid[i][d]));
              mid[i][d]      = m;
            }
      }
    check(tag + "normals at the middle: the distance stays 2a to 1e-13, in "
                "at most 10 projections",
          std::abs(distance_after(x, u, dt) - 2. * a) < 1e-13 &&
            repetitions <= 10);
    check(tag + "the pair stays glued (the pull pays back part of the glue)",
          middle.n_glued() == 1);

    // Rows that are not glued ignore the middle positions.
    Settings inelastic = settings;
    inelastic.model    = Model::inelastic;
    ContactProjector        plain(inelastic), with_middle(inelastic);
    const std::vector<Vec3> approach = {{{1., 0.3, 0.}}, {{-1., -0.2, wz}}};
    std::vector<Vec3>       u_plain, u_middle;
    plain.project(x, radii, approach, dt, u_plain);
    with_middle.project(x, radii, approach, dt, u_middle, mid);
    bool same = true;
    for (unsigned i = 0; i < 2; ++i)
      for (unsigned d = 0; d < 3; ++d)
        same = same && u_plain[i][d] == u_middle[i][d];
    check(tag + "an inelastic projection is the same with the middle", same);

    bool refused = false;
    try
      {
        middle.project(x, radii, turn, dt, u, std::vector<Vec3>(1));
      }
    catch (const ContactError &e)
      {
        refused = std::string(e.what()).find("normal positions have 1 "
                                             "entries for 2 particles") !=
                  std::string::npos;
      }
    check(tag + "a middle with 1 entry for 2 particles is refused", refused);
  }
} // namespace

int
main()
{
  run(2);
  run(3);
  return TestTools::failures() == 0 ? 0 : 1;
}
