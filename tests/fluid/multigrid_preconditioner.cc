// The geometric multigrid preconditioner (Fluid/Linear solver/Preconditioner
// = GMG) against known answers: on the exact rigid inclusion (2D, off the
// mesh's symmetry) it gives the solution of the ML AMG to the linear
// tolerance, omega within 0.5 % of -g/2, and FGMRES iterations per Uzawa
// solve that do not grow with the maximum level as 1/h would (at most x2 over
// two levels, where 1/h is x4). Velocity degree 3 and a 3D case run through
// the same code.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <cmath>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int dim,
    const unsigned int level,
    const std::string &preconditioner,
    const unsigned int degree = 2)
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
      << "  set Velocity degree = " << degree << "\n"
      << "  subsection Linear solver\n    set Tolerance = 1e-8\n"
      << "    set Preconditioner = " << preconditioner << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = " << (dim == 2 ? "0.15" : "0.2")
      << "\n  set Positions = "
      << (dim == 2 ? "0.53, 0.48" : "0.53, 0.48, 0.51") << "\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 2\n"
      << "  set Minimum level = 2\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

double
per_solve(const Fidus::RunSummary &s)
{
  return double(s.max_linear_iterations) / s.max_uzawa_iterations;
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const auto amg = run(2, 7, "AMG");
  const auto gmg = run(2, 7, "GMG");
  check_range("2D level 7: GMG omega minus AMG omega, relative to g/2",
              std::abs(gmg.omega_error - amg.omega_error),
              0.,
              1e-5);
  check_range("2D level 7: GMG relative omega error", gmg.omega_error, 0., 0.005);
  check_range("2D level 7: GMG L2 error of u / AMG L2 error of u",
              gmg.u_l2_error / amg.u_l2_error,
              0.999,
              1.001);

  const auto coarse = run(2, 6, "GMG");
  const auto fine   = run(2, 8, "GMG");
  check_range("2D: FGMRES per Uzawa solve, level 8 / level 6",
              per_solve(fine) / per_solve(coarse),
              0.,
              2.);

  const auto q3 = run(2, 6, "GMG", 3);
  check_range("2D Q3 level 6: GMG relative omega error", q3.omega_error, 0., 0.005);

  const auto three = run(3, 4, "GMG");
  check_range("3D level 4: GMG relative omega error",
              three.omega_error,
              0.,
              0.01);
  return exit_code();
}
