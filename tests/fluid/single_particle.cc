// One free particle in linear shear (validation.md case 3): at the centre of
// the unit box it rotates at -g/2 and does not translate (by symmetry; the
// confinement correction is below 1 % for a = 0.05); off-centre at y = 0.6 it
// does not move across the streamlines (U_y = 0) and follows the flow,
// U_x ~ g (y - 0.5). 2D and 3D, rigidity residual below its tolerance; the
// 2D centre case once more with the ILU smoother of the velocity AMG.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int dim,
    const std::string &position,
    unsigned int       level,
    const std::string &smoother = "Chebyshev")
{
  std::ostringstream prm;
  prm << "set Dimension = " << dim << "\n"
      << "set Output directory = output_" << dim << "d\n"
      << "subsection Domain\n"
      << "  set Lower left = " << (dim == 2 ? "0, 0" : "0, 0, 0") << "\n"
      << "  set Upper right = " << (dim == 2 ? "1, 1" : "1, 1, 1") << "\n"
      << "end\n"
      << "subsection Fluid\n  set Rigidity tolerance = 2e-4\n"
         "  set Rigidity measure = box\n"
      << "  subsection Linear solver\n    set AMG smoother type = " << smoother
      << "\n    set AMG smoother sweeps = " << (smoother == "ILU" ? 1 : 4)
      << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = 0.05\n  set Positions = "
      << position << "\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = " << (dim == 2 ? 3 : 2) << "\n"
      << "  set Minimum level = " << (dim == 2 ? 3 : 2) << "\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

void
check(const std::string &name, const Fidus::RunSummary &s, const double y)
{
  const double g = 1., a = 0.05;
  const auto  &U = s.velocities[0];
  const auto  &W = s.omegas[0];
  if (y == 0.5)
    {
      check_range(name + ": omega_z / (-g/2)", W[2] / (-0.5 * g), 0.99, 1.01);
      check_range(name + ": |U| / (g a)",
                  std::sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2]) / (g * a),
                  0.,
                  0.01);
    }
  else
    {
      check_range(name + ": |U_y| / (g a)", std::abs(U[1]) / (g * a), 0., 0.01);
      check_range(name + ": U_x / (g (y - 0.5))",
                  U[0] / (g * (y - 0.5)),
                  0.95,
                  1.05);
    }
  check_range(name + ": rigidity residual", s.max_rigidity_residual, 0., 2e-4);
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  check("2D centre", run(2, "0.5, 0.5", 7), 0.5);
  check("2D y = 0.6", run(2, "0.5, 0.6", 7), 0.6);
  // The same physics with the other AMG smoother choice.
  check("2D centre, ILU smoother", run(2, "0.5, 0.5", 7, "ILU"), 0.5);
  check("3D centre", run(3, "0.5, 0.5, 0.5", 4), 0.5);
  return exit_code();
}
