// Bad input to the projector: each case must throw ContactError with a
// message that names what is wrong (particle, pair and overlap, wall, dt),
// and a valid call afterwards must still work.

#include "test_tools.h"

#include <cmath>
#include <fidus/contact/contact_projector.h>
#include <limits>
#include <string>

using namespace Fidus::Contact;

int
main()
{
  for (const Model model : {Model::none, Model::inelastic, Model::gluey})
    {
      Settings settings;
      settings.dimension = 2;
      settings.model     = model;
      ContactProjector  projector(settings);
      const std::string head =
        model == Model::none ? "none" :
                               (model == Model::gluey ? "gluey" : "inelastic");

      std::vector<Vec3>   x = {Vec3{{0., 0., 0.}},
                               Vec3{{0.3, 0., 0.}},
                               Vec3{{0., 0.3, 0.}},
                               Vec3{{0.3, 0.3, 0.}}};
      std::vector<double> a(4, 0.1);
      std::vector<Vec3>   u(4, Vec3{{1., 0., 0.}}), out;

      auto nan_u  = u;
      nan_u[3][1] = std::numeric_limits<double>::quiet_NaN();
      TestTools::expect_error(head + ": NaN velocity names the particle",
                              [&] {
                                projector.project(x, a, nan_u, 0.01, out);
                              },
                              {"particle 3", "not finite"});
      auto inf_u  = u;
      inf_u[2][0] = std::numeric_limits<double>::infinity();
      TestTools::expect_error(head + ": infinite velocity names the particle",
                              [&] {
                                projector.project(x, a, inf_u, 0.01, out);
                              },
                              {"particle 2", "not finite"});
      for (const double dt :
           {0., -0.01, std::numeric_limits<double>::quiet_NaN()})
        TestTools::expect_error(head + ": dt = " + std::to_string(dt) +
                                  " rejected",
                                [&] { projector.project(x, a, u, dt, out); },
                                {"time step dt", "positive"});
      TestTools::expect_error(
        head + ": size mismatch",
        [&] {
          projector.project(x, std::vector<double>(3, 0.1), u, 0.01, out);
        },
        {"size mismatch", "3 radii"});
      TestTools::expect_error(head + ": radius <= 0",
                              [&] {
                                auto b = a;
                                b[1]   = 0.;
                                projector.project(x, b, u, 0.01, out);
                              },
                              {"radius of particle 1"});

      if (model != Model::none)
        {
          // Particles 1 and 3 overlap by 0.01.
          auto y  = x;
          y[3][1] = 0.19;
          TestTools::expect_error(
            head + ": initial overlap names the pair and overlap",
            [&] { projector.project(y, a, u, 0.01, out); },
            {"particles 1 and 3", "overlap by 0.01"});
          ContactProjector with_wall(settings);
          with_wall.set_walls({Wall{1, -0.095, 1, Vec3{{0., 0., 0.}}}});
          TestTools::expect_error(
            head + ": overlap with a wall names particle and wall",
            [&] { with_wall.project(x, a, u, 0.01, out); },
            {"particle 0 and wall 0", "overlap by 0.005"});
        }
      TestTools::expect_error(
        head + ": wall with inflow is not a wall",
        [&] {
          projector.set_walls({Wall{1, -1., 1, Vec3{{0., 0.5, 0.}}}});
        },
        {"wall 0", "normal component"});
      TestTools::expect_error(head + ": wall axis outside the dimension",
                              [&] {
                                projector.set_walls({Wall{2, 0., 1, Vec3{}}});
                              },
                              {"wall 0", "axis 2"});

      // A valid call still works after all this.
      bool ok = true;
      try
        {
          const auto statistics = projector.project(x, a, u, 0.01, out);
          ok = statistics.converged && out.size() == 4 && out[0][0] == 1.;
        }
      catch (...)
        {
          ok = false;
        }
      TestTools::check(head + ": valid input accepted afterwards", ok);
    }

  TestTools::expect_error("dimension 4 rejected",
                          [] {
                            Settings s;
                            s.dimension = 4;
                            ContactProjector p(s);
                          },
                          {"dimension"});
  return TestTools::failures() == 0 ? 0 : 1;
}
