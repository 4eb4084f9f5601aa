// A dense random packing of 1000 polydisperse particles, in 2D and in 3D,
// squeezed by the converging velocity field u = -(x - x_c) for many steps
// until it jams (more active contacts than particles). With `inelastic` and
// `gluey` no gap may go below -tolerance after any step, every projection
// converges and satisfies the KKT conditions; with `none` the same field
// makes the particles overlap, which shows the model is what prevents it.

#include "kkt_check.h"
#include "test_tools.h"

#include <cstdio>
#include <fidus/contact/contact_driver.h>

using namespace Fidus::Contact;

int
main()
{
  const double tolerance = 1e-11;
  for (const unsigned dim : {2u, 3u})
    {
      TestTools::Random   random(7);
      std::vector<Vec3>   x;
      std::vector<double> a;
      const std::size_t   n       = 1000;
      const double        radius  = dim == 2 ? 0.0105 : 0.045;
      const int           n_steps = dim == 2 ? 75 : 50;
      const double        dt      = 0.005;
      TestTools::random_packing(random,
                                dim,
                                n,
                                0.8 * radius,
                                1.2 * radius,
                                0.,
                                1.,
                                0.,
                                x,
                                a);

      for (const Model model : {Model::inelastic, Model::gluey, Model::none})
        {
          Settings settings;
          settings.dimension = dim;
          settings.model     = model;
          settings.tolerance = tolerance;
          ContactDriver driver(settings, x, a, [dim](const Vec3 &p, double) {
            Vec3 v{{0., 0., 0.}};
            for (unsigned d = 0; d < dim; ++d)
              v[d] = -(p[d] - 0.5);
            return v;
          });
          double        min_gap   = 1.;
          double        kkt       = 0.;
          bool          converged = true;
          unsigned int  active = 0, glued = 0;
          for (int step = 0; step < n_steps; ++step)
            {
              const auto statistics = driver.step(dt);
              converged             = converged && statistics.converged;
              active                = statistics.n_active;
              glued                 = statistics.n_glued;
              if (model != Model::none)
                kkt = std::max(kkt,
                               KKT::check(driver.projector(),
                                          {},
                                          {},
                                          driver.predicted_velocities(),
                                          driver.velocities(),
                                          dt)
                                 .worst());
              min_gap = std::min(min_gap, driver.minimum_gap(0.));
            }

          const std::string head =
            std::to_string(dim) + "D " + std::to_string(n) + " particles, " +
            std::to_string(n_steps) + " steps, " +
            (model == Model::none ?
               "none" :
               (model == Model::gluey ? "gluey" : "inelastic"));
          char line[256];
          if (model == Model::none)
            {
              std::snprintf(line,
                            sizeof line,
                            "%s: overlaps appear (smallest gap < -0.1 a)",
                            head.c_str());
              TestTools::check(line, min_gap < -0.1 * 0.8 * radius);
              continue;
            }
          std::snprintf(line,
                        sizeof line,
                        "%s: no gap below -%.0e after any step",
                        head.c_str(),
                        tolerance);
          TestTools::check(line, min_gap >= -tolerance);
          TestTools::check(head + ": all projections converged", converged);
          TestTools::check(head + ": KKT of every projection within 1e-11",
                           kkt <= 1.001 * tolerance);
          TestTools::check(head + ": jammed at the end (active contacts > " +
                             "particles)",
                           active > n);
          if (model == Model::gluey)
            TestTools::check(head + ": glued pairs > particles", glued > n);
        }
    }
  return TestTools::failures() == 0 ? 0 : 1;
}
