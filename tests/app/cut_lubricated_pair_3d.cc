// The sub-grid lubrication correction on the 3D cut finite element
// (Fluid/Model = cut finite element with Fluid/Lubrication correction, in
// 3D): the fluid resolves every gap down to Fluid/Cut minimum gap h_s and
// sees the narrower ones at it; the bonds add the squeeze and sliding
// resistance between h_s and the true gap (doc/theory/lubrication.md, "With
// the cut finite element").
//
// Two spheres of radius 0.15 in the unit box at rest, 0.01 a apart on a line
// at 135° in the x-y plane, pushed together by opposite forces of 1, at
// level 3 (a/h = 1.2 away from the particles; one cell across a resolved
// gap). The approach speed must not depend on where the fluid hands the gap
// over to the bonds: with h_s = 0.2 a and 0.3 a it agrees within 3 %
// (measured 0.3 %; 0.1 a gives 0.4 % less than 0.2 a), where the fluid
// alone, seeing the gap at 0.2 a, is more than twice as fast (measured 12
// times). Against the cut element that resolves the 0.01 a gap itself (9
// minutes and 16.5 GB, so not a test: contrib/benchmarks/
// cut_lubricated_pair_3d.sh, doc/validation.md) the corrected approach
// speed is 1.005-1.019 (h_s = 0.02-0.3), and at the default h_s = 0.02 the
// sheared pair's closing speed and stresslet 0.994 and 0.986.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

namespace
{
  const double a = 0.15, dt = 1e-4, h = 0.01 * a;

  /// The speed at which the gap closes over one step, with the fluid
  /// resolving gaps down to @p minimum_gap and the correction on or off.
  double
  approach_speed(const double minimum_gap, const bool corrected)
  {
    const double c = std::cos(0.75 * M_PI), s = std::sin(0.75 * M_PI),
                 d = a + 0.5 * h;
    std::ostringstream prm;
    prm.precision(17);
    prm << "set Dimension = 3\nset Output directory = run_output\n"
        << "subsection Domain\n  set Lower left = 0, 0, 0\n"
        << "  set Upper right = 1, 1, 1\n"
        << "  set Boundary condition = linear shear\n"
        << "  set Shear rate = 0\nend\n"
        << "subsection Fluid\n  set Model = cut finite element\n"
        << "  set Cut minimum gap = " << minimum_gap << "\n"
        << "  set Cut gap cells = 1\n"
        << "  set Lubrication correction = " << (corrected ? "true" : "false")
        << "\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = " << 0.5 - d * c << ", " << 0.5 - d * s
        << ", 0.5; " << 0.5 + d * c << ", " << 0.5 + d * s << ", 0.5\n"
        << "  set External force = " << c << ", " << s << ", 0; " << -c << ", "
        << -s << ", 0\nend\n"
        << "subsection Contact\n  set Model = none\n  set Walls = true\n"
        << "  set Roughness = 1e-4\nend\n"
        << "subsection Time stepping\n  set End time = " << dt << "\n"
        << "  set Time step = " << dt << "\nend\n"
        << "subsection Mesh refinement\n"
        << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
        << "  set Maximum level = 5\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
    const std::string f = "run_output/particles.csv";
    const auto        x = csv_column(f, "x"), y = csv_column(f, "y"),
               z   = csv_column(f, "z");
    const auto gap = [&](const unsigned int row) {
      return std::sqrt(std::pow(x[row + 1] - x[row], 2) +
                       std::pow(y[row + 1] - y[row], 2) +
                       std::pow(z[row + 1] - z[row], 2)) -
             2. * a;
    };
    return (gap(0) - gap(2)) / dt;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const double at_02 = approach_speed(0.2, true);
  const double at_03 = approach_speed(0.3, true);
  check_range("pushed pair at 0.01 a: corrected, h_s = 0.3 a / h_s = 0.2 a",
              at_03 / at_02,
              0.97,
              1.03);
  check_range("pushed pair at 0.01 a: the fluid alone at 0.2 a / corrected",
              approach_speed(0.2, false) / at_02,
              2.,
              1e3);
  return exit_code();
}
