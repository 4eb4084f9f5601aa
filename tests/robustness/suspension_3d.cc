// Stress test: 24 spheres (volume fraction 0.05) between sliding walls in
// 3D (periodic in x and z), fictitious-domain fluid on a coarse mesh, one
// step with 'gluey': bounded Uzawa and FGMRES iterations, no NaN, no gap
// below -tolerance. Particles near the periodic faces have their solid
// images on the other side.

#include "../fidus_test.h"
#include "stress_tools.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const double       a = 0.08;
  const auto         x = random_layout(3, 24, a, 5e-3, 3);
  std::ostringstream prm;
  prm << "set Dimension = 3\n"
      << "set Output directory = suspension_3d\n"
      << "subsection Domain\n  set Lower left = 0, 0, 0\n"
      << "  set Upper right = 1, 1, 1\n"
      << "  set Boundary condition = sliding walls\nend\n"
      << "subsection Fluid\n  set Rigidity tolerance = 1e-2\n"
         "  set Rigidity measure = box\n"
      << "  set Maximum Uzawa iterations = 10\nend\n"
      << "subsection Particles\n  set Radius = " << a << "\n"
      << "  set Positions = " << positions_entry(x, 3) << "\nend\n"
      << "subsection Contact\n  set Model = gluey\nend\n"
      << "subsection Time stepping\n  set End time = 0.05\n"
      << "  set Time step = 0.05\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 2\n  set Minimum level = 2\n"
      << "  set Maximum level = 4\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  const Fidus::RunSummary s =
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  check_range("particles", s.positions.size(), 20, 100);
  check_range("finite state", finite_state(s), 1, 1);
  check_range("minimum gap", s.min_gap, -1e-9 * a, 1.);
  // Measured (commit 256e7ce): 1 Uzawa iteration and 55 FGMRES
  // iterations; the caps are 10 and 10 x 2000.
  check_range("largest Uzawa iterations", s.max_uzawa_iterations, 1, 2);
  check_range("FGMRES iterations per step", s.max_linear_iterations, 1, 90);
  return exit_code();
}
