// A projection that stops short of its tolerance leaves overlaps; the next
// projection accepts up to twice that projection's residual in its input
// and pushes them apart, instead of stopping the run (a dense frictional
// packing can stall, doc/theory/contact.md). Here no iteration is allowed,
// so a projection converges only if the predicted velocities are already
// admissible: two touching discs (a = 0.1) pushed together at 0.1 each for
// one step of 0.1 overlap by 0.02, which is the first projection's
// residual; the second step pulls them apart at 0.5 each and must be
// accepted, converge, and return the tolerated overlap to the settings'
// value. A disc pushed into a wall does the same, and an overlap beyond
// the tolerated one is still refused.

#include "test_tools.h"

#include <cmath>
#include <fidus/contact/contact_driver.h>
#include <fidus/contact/contact_error.h>

using namespace Fidus::Contact;
using TestTools::check;

namespace
{
  Settings
  no_iterations()
  {
    Settings s;
    s.dimension      = 2;
    s.model          = Model::inelastic;
    s.max_iterations = 0;
    return s;
  }

  /// Velocity towards x = 0.5 at 0.1 before t = 0.05, away at 0.5 after.
  Vec3
  push_then_pull(const Vec3 &x, const double t)
  {
    const double side = x[0] < 0.5 ? 1. : -1.;
    return Vec3{{t < 0.05 ? 0.1 * side : -0.5 * side, 0., 0.}};
  }
} // namespace

int
main()
{
  const double dt = 0.1;
  {
    ContactDriver driver(no_iterations(),
                         {Vec3{{0.4, 0.5, 0.}}, Vec3{{0.6, 0.5, 0.}}},
                         {0.1, 0.1},
                         push_then_pull);
    const double  base  = driver.projector().tolerated_overlap();
    const auto    first = driver.step(dt);
    const double  gap   = driver.minimum_gap(0.);
    check("pair: the first projection does not converge, overlap 0.02",
          !first.converged && std::abs(gap + 0.02) < 1e-12);
    check("pair: the overlap left is within the residual",
          -gap <= first.residual * (1. + 1e-12));
    check("pair: twice the residual is tolerated next",
          std::abs(driver.projector().tolerated_overlap() -
                   2. * first.residual) < 1e-15 &&
            driver.projector().tolerated_overlap() > 1e6 * base);
    bool accepted         = true;
    bool second_converged = false;
    try
      {
        second_converged = driver.step(dt).converged;
      }
    catch (const ContactError &)
      {
        accepted = false;
      }
    check("pair: the overlapping input is accepted and pulled apart",
          accepted && second_converged && driver.minimum_gap(0.) > 0.);
    check("pair: after a converged projection the tolerance is the settings'",
          driver.projector().tolerated_overlap() == base);
  }
  {
    // A disc pushed into the wall y = 0 at 0.3 for one step from a gap of
    // 0.01: overlap 0.02; then pulled off.
    ContactDriver driver(no_iterations(),
                         {Vec3{{0.5, 0.11, 0.}}},
                         {0.1},
                         [](const Vec3 &, const double t) {
                           return Vec3{{0., t < 0.05 ? -0.3 : 0.5, 0.}};
                         });
    driver.set_walls({Wall{1, 0., 1, Vec3{{0., 0., 0.}}}});
    const auto   first = driver.step(dt);
    const double gap   = driver.minimum_gap(0.);
    check("wall: the first projection leaves an overlap of 0.02",
          !first.converged && std::abs(gap + 0.02) < 1e-12);
    bool accepted = true;
    try
      {
        driver.step(dt);
      }
    catch (const ContactError &)
      {
        accepted = false;
      }
    check("wall: accepted next and pulled off",
          accepted && driver.minimum_gap(0.) > 0.);
  }
  {
    // Converged projections keep the settings' tolerance: two discs that
    // start 0.001 into each other are refused.
    ContactDriver driver(no_iterations(),
                         {Vec3{{0.4, 0.5, 0.}}, Vec3{{0.599, 0.5, 0.}}},
                         {0.1, 0.1},
                         push_then_pull);
    bool          refused = false;
    try
      {
        driver.step(dt);
      }
    catch (const ContactError &)
      {
        refused = true;
      }
    check("an overlap in the input of a first projection is refused", refused);
  }
  return TestTools::failures() != 0;
}
