// The exact rigid inclusion at random positions (2D, the seed's radius
// a = 0.05, four positions drawn with a fixed seed in the middle of the unit
// box): the particle's velocity error depends on where it sits relative to
// the mesh, so a centred or grid-aligned particle does not show it. Exact:
// U = 0, omega = -g/2. At one position the error can be smaller on the
// coarser mesh (it changes sign with the position; measured: 4e-6 at
// level 6 against 5e-4 at level 8 at the first position), so what is
// checked is the largest over the positions: from maximum level 6 to 8
// (the surface's cells halve twice) the largest omega error falls at least
// 4x and the largest |U| / (g a) at least 2x, and at level 8 they are below
// 1 % and 0.5 %. The errors per position go to measured_values.txt.

#include "../fidus_test.h"

#include <algorithm>
#include <cstdint>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <fstream>
#include <random>
#include <vector>

using namespace FidusTest;

Fidus::RunSummary
run(const double x, const double y, const unsigned int level)
{
  std::ostringstream prm;
  prm.precision(17);
  prm
    << "set Dimension = 2\nset Output directory = run_output\n"
    << "subsection Domain\n"
    << "  set Boundary condition = exact rigid inclusion\nend\n"
    // Solid retraction 0: the seed's model, in which the bounds below were
    // measured.
    << "subsection Fluid\n  set Solid retraction = 0\n  set Rigidity tolerance = 5e-4\n"
       "  set Rigidity measure = box\n"
    << "  subsection Linear solver\n    set Tolerance = 1e-8\n  end\nend\n"
    << "subsection Particles\n  set Radius = 0.05\n"
    << "  set Positions = " << x << ", " << y << "\nend\n"
    << "subsection Time stepping\n  set End time = 0\nend\n"
    << "subsection Mesh refinement\n"
    << "  set Initial global refinement = 3\n"
    << "  set Minimum level = 3\n"
    << "  set Maximum level = " << level << "\nend\n"
    << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  // The engine's raw output is the same everywhere (unlike the standard
  // distributions): positions in [0.4, 0.6]^2.
  std::mt19937 engine(2026);
  const auto   draw = [&engine]() {
    return 0.4 + 0.2 * double(engine()) / 4294967296.;
  };
  std::ofstream table("measured_values.txt", std::ios::app);
  table << "x y  omega error level 6, 8  |U|/(g a) level 6, 8\n";
  double omega_6 = 0., omega_8 = 0., translation_6 = 0., translation_8 = 0.;
  for (unsigned int p = 0; p < 4; ++p)
    {
      const double x      = draw();
      const double y      = draw();
      const auto   coarse = run(x, y, 6);
      const auto   fine   = run(x, y, 8);
      table << x << " " << y << "  " << coarse.omega_error << " "
            << fine.omega_error << "  " << coarse.translation_error << " "
            << fine.translation_error << "\n";
      omega_6       = std::max(omega_6, coarse.omega_error);
      omega_8       = std::max(omega_8, fine.omega_error);
      translation_6 = std::max(translation_6, coarse.translation_error);
      translation_8 = std::max(translation_8, fine.translation_error);
    }
  check_range("largest relative omega error, level 6 / level 8",
              omega_6 / omega_8,
              4.,
              1e6);
  check_range("level 8: largest relative omega error", omega_8, 0., 0.01);
  check_range("largest |U| / (g a), level 6 / level 8",
              translation_6 / translation_8,
              2.,
              1e6);
  check_range("level 8: largest |U| / (g a)", translation_8, 0., 0.005);
  return exit_code();
}
