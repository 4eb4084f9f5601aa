// A sphere too small for the mesh stops the run with a message that names
// the remedy, instead of moving with an unbounded velocity. The bidisperse
// bulk scene's spheres (radii 0.04 and 0.056 at phi = 0.3, generator seed
// 1, prm/rheology_bulk_3d_bidisperse.prm) on a uniform mesh of level 4
// (h = 0.0625): with the default 'Solid retraction' of 0.3 the small
// spheres' solid is a ball of radius 0.021, which holds a few quadrature
// points so close together that the rotation of the rigid fit is not
// determined; without the check, eleven of them left step 0 with
// velocities of 1e11 and rotations of 1e14 while the flow stayed below the
// walls' speed 0.5. Checked: the run stops with a RunError naming 'Solid
// retraction' and 'Maximum level'; with 'Solid retraction = 0' (a radius
// of 0.04 held rigid) the same mesh passes the check and every sphere's
// velocity at step 0 is bounded by the walls' speed and its rotation by
// the shear rate.

#include "../fidus_test.h"

#include <algorithm>
#include <cmath>
#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>
#include <string>

using namespace FidusTest;

namespace
{
  Fidus::RunSummary
  run(const std::string &retraction)
  {
    std::ostringstream prm;
    prm << "set Dimension = 3\nset Output directory = run_output\n"
        << "subsection Domain\n  set Lower left = 0, 0, 0\n"
        << "  set Upper right = 1, 1, 1\n"
        << "  set Boundary condition = sliding walls\nend\n"
        << "subsection Fluid\n  set Shared cells = fluid\n"
        << "  set Solid retraction = " << retraction << "\nend\n"
        << "subsection Particles\n  subsection Generator\n"
        << "    set Fraction = 0.3\n    set Radii = 0.04, 0.056\n"
        << "    set Radius weights = 0.733, 0.267\n"
        << "    set Minimum separation = 0.004\n    set Seed = 1\n  end\nend\n"
        << "subsection Time stepping\n  set End time = 0\nend\n"
        << "subsection Mesh refinement\n"
        << "  set Initial global refinement = 4\n  set Minimum level = 4\n"
        << "  set Maximum level = 4\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  std::string message;
  try
    {
      run("0.3");
    }
  catch (const Fidus::RunError &e)
    {
      message = e.what();
    }
  check_range("retraction 0.3 stops the run, naming the rotation's fit, "
              "'Solid retraction' and 'Maximum level' (1: it does)",
              message.find("to fit a rigid rotation") != std::string::npos &&
                message.find("Fluid/Solid retraction") != std::string::npos &&
                message.find("Mesh refinement/Maximum level") !=
                  std::string::npos,
              1,
              1);

  const Fidus::RunSummary s  = run("0");
  double                  vu = 0., vw = 0.;
  for (std::size_t i = 0; i < s.velocities.size(); ++i)
    for (unsigned int d = 0; d < 3; ++d)
      {
        vu = std::max(vu, std::abs(s.velocities[i][d]));
        vw = std::max(vw, std::abs(s.omegas[i][d]));
      }
  print_value("spheres", double(s.velocities.size()), 3);
  check_range("retraction 0: largest velocity component / wall speed 0.5",
              vu / 0.5,
              0.,
              1.);
  check_range("retraction 0: largest rotation component / shear rate",
              vw,
              0.,
              1.);
  return exit_code();
}
