// The cut element's sub-grid correction where the fluid's shrinking widens
// a gap above Fluid/Cut minimum gap (doc/theory/lubrication.md, "With the
// cut finite element"). The fluid sees a particle closer than the minimum
// gap h_s to another with its radius reduced, and so every other gap of
// that particle wider than it is; the correction gives each such gap the
// resistance between its true width and its width in the fluid, not only
// the gaps below h_s.
//
// Three discs of radius 0.1 on a line in the unit square: A and B 0.005 a
// apart (both shrunk by 0.0475 a for the fluid at h_s = 0.1), B and C
// 0.15 a apart, above h_s (0.1975 a in the fluid). The closing speed of B
// and C, pushed together by opposite forces in a box at rest and carried
// together by a linear shear on the compressional axis (135°), against
// the cut element that resolves every gap (minimum gap 1e-4, no
// correction), within 5 % (measured 1.029 and 1.003). Before the widened
// gaps were corrected, the pushed pair closed 1.43 times and the sheared
// one 1.39 times as fast as the resolved ones; with the widened gaps
// resolved at the true radii instead of the fluid's, 1.049 and 1.022.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

namespace
{
  const double a = 0.1, dt = 1e-4, h_ab = 0.005 * a, h_bc = 0.15 * a;

  /// The speed at which the gap of B and C closes over one step of @p dt:
  /// the discs on a line at @p angle (degrees from the x axis) through the
  /// box's centre, B and C pushed together by unit forces along it
  /// (@p pushed, box at rest) or carried by the shear of rate 1.
  double
  closing_speed(const bool resolved, const double angle, const bool pushed)
  {
    const double c = std::cos(angle * M_PI / 180.),
                 s = std::sin(angle * M_PI / 180.);
    // B at the origin of the line, A before it, C after it; the middle of
    // the B-C gap at the box's centre.
    const double xb = -(a + 0.5 * h_bc), xa = xb - 2. * a - h_ab,
                 xc = a + 0.5 * h_bc;
    std::ostringstream prm;
    prm.precision(17);
    prm << "set Dimension = 2\nset Output directory = run_output\n"
        << "subsection Domain\n  set Boundary condition = linear shear\n"
        << "  set Shear rate = " << (pushed ? 0. : 1.) << "\nend\n"
        << "subsection Fluid\n  set Model = cut finite element\n"
        << "  set Cut linear solver = direct\n"
        << "  set Cut minimum gap = " << (resolved ? "1e-4" : "0.1") << "\n"
        << "  set Lubrication correction = " << (resolved ? "false" : "true")
        << "\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = ";
    for (const double x : {xa, xb, xc})
      prm << 0.5 + x * c << ", " << 0.5 + x * s << (x == xc ? "\n" : "; ");
    if (pushed)
      prm << "  set External force = 0, 0; " << c << ", " << s << "; " << -c
          << ", " << -s << "\n";
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
    const auto        x = csv_column(f, "x"), y = csv_column(f, "y");
    // Rows: A, B, C at step 0, then at step 1.
    const auto gap = [&](const unsigned int row) {
      return std::hypot(x[row + 2] - x[row + 1], y[row + 2] - y[row + 1]) -
             2. * a;
    };
    return (gap(0) - gap(3)) / dt;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  check_range("pushed: B-C closing, corrected / resolved",
              closing_speed(false, 0., true) / closing_speed(true, 0., true),
              0.95,
              1.05);
  check_range("sheared at 135°: B-C closing, corrected / resolved",
              closing_speed(false, 135., false) /
                closing_speed(true, 135., false),
              0.95,
              1.05);
  return exit_code();
}
