// The direct Stokes solver (Fluid/Linear solver/Method = direct) against
// FGMRES on the rigid inclusion with the exact solution on the boundary
// (validation.md case 3b), 2D and 3D, on 1 and 2 ranks:
// - it runs no FGMRES iteration, and the Uzawa loop takes as many
//   iterations as with FGMRES;
// - the rigid velocity and the velocity error agree with FGMRES at 1e-10
//   to 1e-6 (both solve the same system; only round-off and the FGMRES
//   tolerance separate them);
// - in 2D at level 7 the rotation is within 0.5 % of the exact -g/2 and
//   the translation within 0.5 % of g a, as exact_inclusion asserts for
//   FGMRES;
// - 'auto' is direct in 2D and iterative in 3D.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int dim, const unsigned int level, const std::string &method)
{
  std::ostringstream prm;
  prm << "set Dimension = " << dim << "\n"
      << "set Output directory = run_output\n"
      << "subsection Domain\n"
      << "  set Lower left = " << (dim == 2 ? "0, 0" : "0, 0, 0") << "\n"
      << "  set Upper right = " << (dim == 2 ? "1, 1" : "1, 1, 1") << "\n"
      << "  set Boundary condition = exact rigid inclusion\n"
      << "end\n"
      << "subsection Fluid\n  set Rigidity tolerance = 5e-4\n"
         "  set Rigidity measure = box\n"
      << "  subsection Linear solver\n    set Tolerance = 1e-10\n"
      << "    set Method = " << method << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = " << (dim == 2 ? "0.15" : "0.2")
      << "\n  set Positions = "
      << (dim == 2 ? "0.503, 0.488" : "0.503, 0.488, 0.51") << "\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 2\n"
      << "  set Minimum level = 2\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

void
compare(const unsigned int dim, const unsigned int level)
{
  const std::string name =
    std::to_string(dim) + "D level " + std::to_string(level) + ": ";
  const Fidus::RunSummary fgmres    = run(dim, level, "iterative");
  const Fidus::RunSummary direct    = run(dim, level, "direct");
  const Fidus::RunSummary automatic = run(dim, level, "auto");

  check_range(name + "FGMRES iterations of the direct solver",
              direct.max_linear_iterations,
              0.,
              0.);
  check_range(name + "FGMRES iterations of the iterative solver",
              fgmres.max_linear_iterations,
              1.,
              1e9);
  check_range(name + "Uzawa iterations, direct minus iterative",
              double(direct.max_uzawa_iterations) -
                double(fgmres.max_uzawa_iterations),
              0.,
              0.);
  check_range(name + "'auto' is " + (dim == 2 ? "direct" : "iterative") +
                ": its FGMRES iterations minus the " +
                (dim == 2 ? "direct" : "iterative") + " run's",
              double(automatic.max_linear_iterations) -
                double(dim == 2 ? direct.max_linear_iterations :
                                  fgmres.max_linear_iterations),
              0.,
              0.);

  // Rotation and translation scale: g/2 and g a with g = 1.
  const double a                = dim == 2 ? 0.15 : 0.2;
  double       omega_difference = 0., u_difference = 0.;
  for (unsigned int d = 0; d < 3; ++d)
    {
      omega_difference =
        std::max(omega_difference,
                 std::abs(direct.omegas[0][d] - fgmres.omegas[0][d]) / 0.5);
      u_difference =
        std::max(u_difference,
                 std::abs(direct.velocities[0][d] - fgmres.velocities[0][d]) /
                   a);
    }
  check_range(name + "|omega direct - omega iterative| / (g/2)",
              omega_difference,
              0.,
              1e-6);
  check_range(name + "|U direct - U iterative| / (g a)",
              u_difference,
              0.,
              1e-6);
  check_range(name + "L2 velocity error, direct / iterative",
              direct.u_l2_error / fgmres.u_l2_error,
              1. - 1e-6,
              1. + 1e-6);
  if (dim == 2 && level >= 7)
    {
      check_range(name + "direct: relative omega error",
                  direct.omega_error,
                  0.,
                  0.005);
      check_range(name + "direct: |U| / (g a)",
                  direct.translation_error,
                  0.,
                  0.005);
    }
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  compare(2, 7);
  compare(3, 3);
  return exit_code();
}
