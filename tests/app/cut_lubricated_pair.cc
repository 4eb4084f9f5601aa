// The sub-grid lubrication correction on the cut finite element
// (Fluid/Model = cut finite element with Fluid/Lubrication correction):
// the fluid resolves every gap down to Fluid/Cut minimum gap (auto: 0.02 of
// the smaller radius with the correction) and sees the narrower ones at it;
// the correction adds the squeeze and sliding resistance between that gap
// and the true one (doc/theory/lubrication.md, "With the cut finite
// element"). The reference is the cut element that resolves the true gap
// itself (minimum gap 1e-4, no correction), on the same mesh rules, so the
// only difference is the gap below the minimum gap. Contact/Roughness is
// 1e-3 here, below every gap, since the correction's resistance stops
// growing at the roughness (at the default 5e-3 the pair at 0.002 a closes
// 4 times faster than the smooth resolved one).
//
// Two discs of radius 0.1 in the unit square, at gaps 0.01 a and 0.002 a:
// - pushed together by opposite forces (box at rest): the corrected
//   approach speed is the resolved one within 5 %, where the fluid alone,
//   seeing the gap at 0.05 a, is more than twice too fast at 0.002 a
//   (measured 30 times);
// - free in a linear shear, on the compressional axis (135°): the closing
//   speed the flow drives, and the pair's stresslet (the fluid's and the
//   correction's), within 5 % of the resolved ones.
// One disc 0.005 a from the box's bottom face (a wall moving with the
// shear): its speed when pushed onto it, and its u_x, omega and stresslet
// when the shear carries it along, within 5 %. (Measured: 0.98-1.02.)
// And the entries: auto gives 0.02 with the correction and 1e-4 without.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

namespace
{
  const double a = 0.1, dt = 1e-4;

  enum class Fluid
  {
    resolved, // minimum gap 1e-4, no correction
    floor,    // minimum gap 0.05, no correction
    corrected // minimum gap auto (0.02), the correction
  };

  /// particles.csv of one step of @p dt of discs at @p positions, pushed
  /// by @p forces (empty: none) in a box at rest, or carried by the linear
  /// shear of rate 1 if there are none. Rows: the particles at step 0, then
  /// at step 1.
  struct Rows
  {
    std::vector<double> x, y, ux, omega, sxy;
  };

  Rows
  run(const Fluid        fluid,
      const std::string &positions,
      const std::string &forces)
  {
    std::ostringstream prm;
    prm.precision(17);
    prm << "set Dimension = 2\nset Output directory = run_output\n"
        << "subsection Domain\n  set Boundary condition = linear shear\n"
        << "  set Shear rate = " << (forces.empty() ? 1. : 0.) << "\nend\n"
        << "subsection Fluid\n  set Model = cut finite element\n"
        << "  set Cut linear solver = direct\n"
        << (fluid == Fluid::resolved ? "  set Cut minimum gap = 1e-4\n" :
            fluid == Fluid::floor    ? "  set Cut minimum gap = 0.05\n" :
                                       "")
        << "  set Lubrication correction = "
        << (fluid == Fluid::corrected ? "true" : "false") << "\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = " << positions << "\n";
    if (!forces.empty())
      prm << "  set External force = " << forces << "\n";
    prm << "end\n"
        << "subsection Contact\n  set Model = none\n  set Walls = true\n"
        << "  set Roughness = 1e-3\nend\n"
        << "subsection Time stepping\n  set End time = " << dt << "\n"
        << "  set Time step = " << dt << "\nend\n"
        << "subsection Mesh refinement\n"
        << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
        << "  set Maximum level = 5\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
    const std::string f = "run_output/particles.csv";
    Rows              r{csv_column(f, "x"),
           csv_column(f, "y"),
           csv_column(f, "ux"),
           csv_column(f, "omega_z"),
           csv_column(f, "stresslet_xy")};
    const auto        lubrication = csv_column(f, "lubrication_stresslet_xy");
    for (std::size_t k = 0; k < r.sxy.size(); ++k)
      r.sxy[k] += lubrication[k];
    return r;
  }

  /// The speed at which the gap @p h of two discs on a line at @p angle
  /// (degrees, from the x axis) closes over one step, pushed by @p force
  /// along that line (force > 0) or carried by the shear (force 0), and
  /// the pair's total stresslet xy (the fluid's and the correction's).
  std::pair<double, double>
  pair_run(const Fluid  fluid,
           const double h,
           const double angle,
           const double force)
  {
    const double c = std::cos(angle * M_PI / 180.),
                 s = std::sin(angle * M_PI / 180.), d = a + 0.5 * h;
    std::ostringstream at, push;
    at.precision(17);
    push.precision(17);
    at << 0.5 - d * c << ", " << 0.5 - d * s << "; " << 0.5 + d * c << ", "
       << 0.5 + d * s;
    if (force > 0.)
      push << force * c << ", " << force * s << "; " << -force * c << ", "
           << -force * s;
    const Rows r   = run(fluid, at.str(), push.str());
    const auto gap = [&](const unsigned int row) {
      return std::hypot(r.x[row + 1] - r.x[row], r.y[row + 1] - r.y[row]) -
             2. * a;
    };
    return {(gap(0) - gap(2)) / dt, r.sxy[0] + r.sxy[1]};
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  // The auto values: the resolution the correction takes over (the pair
  // checks below run at them).
  const auto cut_settings = [](const bool corrected) {
    return Fidus::read_parameters_from_string(
             std::string("set Dimension = 2\nsubsection Fluid\n"
                         "  set Model = cut finite element\n"
                         "  set Lubrication correction = ") +
             (corrected ? "true" : "false") + "\nend\n")
      .cut_element;
  };
  check_range("Cut minimum gap = auto with the correction",
              cut_settings(true).minimum_gap,
              0.02,
              0.02);
  check_range("Cut minimum gap = auto without it",
              cut_settings(false).minimum_gap,
              1e-4,
              1e-4);
  check_range("Cut gap cells = auto with the correction",
              cut_settings(true).gap_cells,
              1,
              1);
  check_range("Cut gap cells = auto without it",
              cut_settings(false).gap_cells,
              2,
              2);

  for (const double h_over_a : {0.01, 0.002})
    {
      const double      h      = h_over_a * a;
      const std::string at     = " at h = " + std::to_string(h_over_a) + " a";
      const double      pushed = pair_run(Fluid::resolved, h, 0., 1.).first;
      check_range("pushed pair: corrected / resolved" + at,
                  pair_run(Fluid::corrected, h, 0., 1.).first / pushed,
                  0.95,
                  1.05);
      if (h_over_a < 0.005)
        check_range("pushed pair: the gap seen at 0.05 a alone / resolved" + at,
                    pair_run(Fluid::floor, h, 0., 1.).first / pushed,
                    2.,
                    1e3);
      const auto sheared   = pair_run(Fluid::resolved, h, 135., 0.);
      const auto corrected = pair_run(Fluid::corrected, h, 135., 0.);
      check_range("sheared pair at 135°: corrected / resolved closing" + at,
                  corrected.first / sheared.first,
                  0.95,
                  1.05);
      check_range("sheared pair at 135°: corrected / resolved stresslet" + at,
                  corrected.second / sheared.second,
                  0.95,
                  1.05);
    }

  // A disc 0.005 a above the bottom face of the box (a wall moving with
  // the shear): pushed onto it, and carried along it by the shear.
  const double      y          = a + 0.005 * a;
  const std::string disc       = "0.5, " + std::to_string(y);
  const auto        wall_speed = [&](const Fluid fluid) {
    const Rows r = run(fluid, disc, "0, -1");
    return (r.y[0] - r.y[1]) / dt;
  };
  check_range("disc pushed onto a wall: corrected / resolved",
              wall_speed(Fluid::corrected) / wall_speed(Fluid::resolved),
              0.95,
              1.05);
  const Rows resolved = run(Fluid::resolved, disc, "");
  const Rows sheared  = run(Fluid::corrected, disc, "");
  check_range("disc sheared along a wall: corrected / resolved u_x",
              sheared.ux[0] / resolved.ux[0],
              0.95,
              1.05);
  check_range("disc sheared along a wall: corrected / resolved omega",
              sheared.omega[0] / resolved.omega[0],
              0.95,
              1.05);
  // The gap pressure's first moment (lubrication_stresslets()): without
  // it this stresslet was 0.69 of the resolved one.
  check_range("disc sheared along a wall: corrected / resolved stresslet",
              sheared.sxy[0] / resolved.sxy[0],
              0.95,
              1.05);
  return exit_code();
}
