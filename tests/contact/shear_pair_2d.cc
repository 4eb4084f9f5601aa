// Validation case 4: two equal discs (a = 0.05) in the free-draining shear
// u = (y - 0.5, 0) (gamma_dot = 1), the paper's start (0.451, 0.51),
// (0.549, 0.49). While in contact the line of centres turns as
// d(phi)/dt = -sin^2(phi), i.e. cot(phi) grows at rate 1, so
// - gluey: the pair stays glued until the mirror image of the entry,
//   glued time 2 |dx_c| / |dy| = 9.798 (dx_c = sqrt(4a^2 - dy^2)), and leaves
//   with the initial cross-stream offset 0.02;
// - inelastic: the pair separates at phi = -pi/2 after half that time and
//   leaves at offset 2a = 0.1.
// Both are checked at two time steps, with the observed order of the errors,
// the KKT conditions of every projection and the gap after every step; the
// model `none` lets the discs pass through each other.

#include "kkt_check.h"
#include "test_tools.h"

#include <cmath>
#include <cstdio>
#include <fidus/contact/contact_driver.h>
#include <string>

using namespace Fidus::Contact;

namespace
{
  struct Result
  {
    double offset       = 0.; ///< |y_2 - y_1| at the end
    double contact_time = 0.; ///< time glued (gluey) or pushing (inelastic)
    double min_gap      = 1.; ///< smallest gap after any step
    double kkt          = 0.; ///< worst KKT error of all projections
    bool   converged    = true;
  };

  Result
  run(const Model model, const double dt)
  {
    Settings settings;
    settings.dimension = 2;
    settings.model     = model;
    ContactDriver driver(settings,
                         {Vec3{{0.451, 0.51, 0.}}, Vec3{{0.549, 0.49, 0.}}},
                         {0.05, 0.05},
                         [](const Vec3 &x, double) {
                           return Vec3{{x[1] - 0.5, 0., 0.}};
                         });
    Result        result;
    const int     n_steps          = static_cast<int>(std::lround(15. / dt));
    unsigned int  steps_in_contact = 0;
    for (int step = 0; step < n_steps; ++step)
      {
        const auto statistics = driver.step(dt);
        result.converged      = result.converged && statistics.converged;
        if (model != Model::none)
          result.kkt = std::max(result.kkt,
                                KKT::check(driver.projector(),
                                           {},
                                           {},
                                           driver.predicted_velocities(),
                                           driver.velocities(),
                                           dt)
                                  .worst());
        // In contact during this step: glued after it (gluey: the glue
        // variable became negative through a compressive push), or pushing
        // (inelastic: lambda > 0).
        if (model == Model::gluey ? driver.projector().n_glued() > 0 :
                                    statistics.n_active > 0)
          ++steps_in_contact;
        result.min_gap = std::min(result.min_gap, driver.minimum_gap(0.1));
      }
    result.contact_time = steps_in_contact * dt;
    const auto &x       = driver.positions();
    result.offset       = std::abs(x[1][1] - x[0][1]);
    return result;
  }
} // namespace

int
main()
{
  const double a          = 0.05;
  const double dy         = 0.02;
  const double dx_contact = std::sqrt(4. * a * a - dy * dy);
  const double glued_time = 2. * dx_contact / dy; // 9.798
  const double dts[2]     = {1e-2, 5e-3};

  std::printf("exact: gluey offset %.4f, glued time %.4f; inelastic offset "
              "%.4f, contact time %.4f\n",
              dy,
              glued_time,
              2. * a,
              0.5 * glued_time);

  double err[2][4]; // [dt][gluey offset, glued time, inel offset, inel time]
  for (int i = 0; i < 2; ++i)
    {
      const double dt = dts[i];
      const Result g  = run(Model::gluey, dt);
      const Result in = run(Model::inelastic, dt);
      err[i][0]       = std::abs(g.offset - dy);
      err[i][1]       = std::abs(g.contact_time - glued_time);
      err[i][2]       = std::abs(in.offset - 2. * a);
      err[i][3]       = std::abs(in.contact_time - 0.5 * glued_time);
      char line[256];

      std::snprintf(line,
                    sizeof line,
                    "dt %.0e gluey final offset %.4f (expected %.2f, tol "
                    "1e-3)",
                    dt,
                    g.offset,
                    dy);
      TestTools::check(line, err[i][0] <= 1e-3);
      std::snprintf(line,
                    sizeof line,
                    "dt %.0e gluey glued time %.2f (expected %.3f, tol 5 dt)",
                    dt,
                    g.contact_time,
                    glued_time);
      TestTools::check(line, err[i][1] <= 5. * dt);
      std::snprintf(line,
                    sizeof line,
                    "dt %.0e inelastic final offset %.4f (expected %.2f, tol "
                    "1e-3)",
                    dt,
                    in.offset,
                    2. * a);
      TestTools::check(line, err[i][2] <= 1e-3);
      std::snprintf(line,
                    sizeof line,
                    "dt %.0e inelastic contact time %.2f (expected %.3f, tol "
                    "5 dt)",
                    dt,
                    in.contact_time,
                    0.5 * glued_time);
      TestTools::check(line, err[i][3] <= 5. * dt);
      std::snprintf(line,
                    sizeof line,
                    "dt %.0e no gap below -1e-11 after any step, all "
                    "projections converged",
                    dt);
      TestTools::check(line,
                       g.min_gap >= -1e-11 && in.min_gap >= -1e-11 &&
                         g.converged && in.converged);
      std::snprintf(line,
                    sizeof line,
                    "dt %.0e KKT of every projection within 1e-11",
                    dt);
      TestTools::check(line, g.kkt <= 1.001e-11 && in.kkt <= 1.001e-11);
    }

  const char *names[4] = {"gluey offset",
                          "gluey glued time",
                          "inelastic offset",
                          "inelastic contact time"};
  for (int q = 0; q < 4; ++q)
    {
      const double order = std::log2(err[0][q] / err[1][q]);
      char         line[256];
      // The inelastic offset converges faster than first order (the release
      // point is where the normal velocity changes sign smoothly), so only
      // "at least first order" is asserted for it.
      const bool ok = q == 2 ? order >= 0.7 : (order >= 0.7 && order <= 1.3);
      std::snprintf(line,
                    sizeof line,
                    "%s error %.2e -> %.2e, observed order %.1f (expected %s)",
                    names[q],
                    err[0][q],
                    err[1][q],
                    order,
                    q == 2 ? ">= 1" : "1");
      TestTools::check(line, ok);
    }

  // Without contact model the discs pass through each other.
  const Result none = run(Model::none, 1e-2);
  char         line[256];
  std::snprintf(line,
                sizeof line,
                "none: discs overlap (smallest gap %.4f < 0), offset stays "
                "%.4f",
                none.min_gap,
                none.offset);
  TestTools::check(line,
                   none.min_gap < -0.01 && std::abs(none.offset - dy) < 1e-12);
  return TestTools::failures() == 0 ? 0 : 1;
}
