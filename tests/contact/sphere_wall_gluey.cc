// Validation case 5: a particle pushed against a wall and pulled back, gluey
// model. With unit weight the multiplier is the blocked velocity, so the glue
// variable -gamma is the blocked displacement: the push at speed 0.2 for
// t < 1 against a wall it reaches at t_c = 0.25 stores 0.2 (1 - t_c) = 0.15;
// the pull at speed 0.6 (t - 1) for t > 1 pays it back when
// 0.3 (t - 1)^2 = 0.15, i.e. the particle leaves the wall at
// t_r = 1 + sqrt(1/2). The wall moves tangentially and the particle has a
// tangential velocity, which a frictionless contact must not change. The
// inelastic model leaves at t = 1 instead. 2D and 3D, two time steps each.

#include "kkt_check.h"
#include "test_tools.h"

#include <cmath>
#include <cstdio>
#include <fidus/contact/contact_driver.h>

using namespace Fidus::Contact;

namespace
{
  struct Result
  {
    double release_time = -1.;
    double final_height = 0.;
    double x_error      = 0.;
    double kkt          = 0.;
    double min_gap      = 1.;
    bool   converged    = true;
  };

  Result
  run(const unsigned dim, const Model model, const double dt)
  {
    const double a = 0.1;
    Settings     settings;
    settings.dimension = dim;
    settings.model     = model;
    Vec3          start{{0.5, 0.15, dim == 3 ? 0.5 : 0.}};
    ContactDriver driver(settings, {start}, {a}, [](const Vec3 &, double t) {
      return Vec3{{0.2, t < 1. - 1e-12 ? -0.2 : 0.6 * (t - 1.), 0.}};
    });
    const std::vector<Wall> walls = {Wall{1, 0., 1, Vec3{{0.3, 0., 0.}}}};
    driver.set_walls(walls);

    Result    result;
    bool      was_in_contact = false;
    const int n_steps        = static_cast<int>(std::lround(2. / dt));
    for (int step = 0; step < n_steps; ++step)
      {
        const auto statistics = driver.step(dt);
        result.converged      = result.converged && statistics.converged;
        result.kkt            = std::max(result.kkt,
                              KKT::check(driver.projector(),
                                         walls,
                                         {},
                                         driver.predicted_velocities(),
                                         driver.velocities(),
                                         dt)
                                .worst());
        const bool in_contact = model == Model::gluey ?
                                  driver.projector().n_glued() > 0 :
                                  statistics.n_active > 0;
        if (was_in_contact && !in_contact && result.release_time < 0.)
          result.release_time = driver.time();
        was_in_contact = was_in_contact || in_contact;
        result.min_gap = std::min(result.min_gap, driver.minimum_gap(0.));
        result.x_error = std::max(result.x_error,
                                  std::abs(driver.positions()[0][0] -
                                           (0.5 + 0.2 * driver.time())));
      }
    result.final_height = driver.positions()[0][1];
    return result;
  }
} // namespace

int
main()
{
  const double t_release = 1. + std::sqrt(0.5);
  // After leaving at t_r the particle rises with 0.6 (t - 1) until t = 2.
  const double height = 0.1 + 0.3 * (1. - (t_release - 1.) * (t_release - 1.));
  std::printf("exact: gluey release at t = %.4f, final height %.4f\n",
              t_release,
              height);
  for (const unsigned dim : {2u, 3u})
    {
      double errors[2];
      int    i = 0;
      for (const double dt : {1e-2, 5e-3})
        {
          const Result g  = run(dim, Model::gluey, dt);
          const Result in = run(dim, Model::inelastic, dt);
          char         line[256];
          std::snprintf(line,
                        sizeof line,
                        "%uD dt %.0e gluey release at t = %.3f (expected "
                        "%.4f, tol 2 dt)",
                        dim,
                        dt,
                        g.release_time,
                        t_release);
          TestTools::check(line,
                           std::abs(g.release_time - t_release) <= 2 * dt);
          std::snprintf(line,
                        sizeof line,
                        "%uD dt %.0e gluey final height %.3f (expected %.4f, "
                        "tol dt)",
                        dim,
                        dt,
                        g.final_height,
                        height);
          TestTools::check(line, std::abs(g.final_height - height) <= dt);
          errors[i++] = std::abs(g.release_time - t_release);
          std::snprintf(line,
                        sizeof line,
                        "%uD dt %.0e inelastic leaves at t = %.3f (expected "
                        "1, tol 2 dt)",
                        dim,
                        dt,
                        in.release_time);
          TestTools::check(line, std::abs(in.release_time - 1.) <= 2 * dt);
          std::snprintf(line,
                        sizeof line,
                        "%uD dt %.0e tangential motion untouched, no "
                        "overlap, converged, KKT within 1e-11",
                        dim,
                        dt);
          TestTools::check(line,
                           g.x_error < 1e-12 && in.x_error < 1e-12 &&
                             g.min_gap >= -1e-11 && in.min_gap >= -1e-11 &&
                             g.converged && in.converged &&
                             g.kkt <= 1.001e-11 && in.kkt <= 1.001e-11);
        }
      char line[256];
      std::snprintf(line,
                    sizeof line,
                    "%uD release time error shrinks with dt (%.4f -> %.4f)",
                    dim,
                    errors[0],
                    errors[1]);
      TestTools::check(line, errors[1] < errors[0]);
    }
  return TestTools::failures() == 0 ? 0 : 1;
}
