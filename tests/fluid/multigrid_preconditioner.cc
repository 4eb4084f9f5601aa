// The geometric multigrid preconditioner (Fluid/Linear solver/Preconditioner
// = GMG) against known answers: on the exact rigid inclusion (2D, off the
// mesh's symmetry) it gives the solution of the ML AMG to the linear
// tolerance, omega within 1 % of -g/2 at level 7, and FGMRES iterations per
// Uzawa solve that do not grow with the maximum level as 1/h would (at most x2
// over two levels, where 1/h is x4). Velocity degree 3 and a 3D case run
// through the same code.

#include "../fidus_test.h"
#include "summary_tools.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

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
         "  set Rigidity measure = box\n"
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
  // The discretisation's error off the mesh's symmetry (the same with AMG).
  check_range("2D level 7: GMG relative omega error",
              gmg.omega_error,
              0.,
              0.01);
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
  check_range("2D Q3 level 6: GMG relative omega error",
              q3.omega_error,
              0.,
              0.005);

  // Two particles closer than their radius (the seed's scene at t = 0):
  // the rigid-body correction changes the preconditioner, not the answer.
  const auto pair = [](const bool        correction,
                       const bool        matrix_free = true,
                       const std::string boundary    = "linear shear",
                       const std::string positions =
                         "0.451, 0.51; 0.549, 0.49") {
    std::ostringstream prm;
    prm << "set Dimension = 2\nset Output directory = run_output\n"
        << "subsection Domain\n  set Boundary condition = " << boundary
        << "\nend\n"
        << "subsection Fluid\n  set Rigidity tolerance = 1e-4\n"
           "  set Rigidity measure = box\n"
        << "  subsection Linear solver\n    set Tolerance = 1e-9\n"
        << "    set Preconditioner = GMG\n    set Rigid-body correction = "
        << (correction ? "true" : "false") << "\n"
        << "    set Matrix-free velocity block = "
        << (matrix_free ? "true" : "false") << "\n  end\nend\n"
        << "subsection Particles\n  set Radius = 0.05\n"
        << "  set Positions = " << positions << "\nend\n"
        << "subsection Time stepping\n  set End time = 0\nend\n"
        << "subsection Mesh refinement\n  set Maximum level = 7\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  };
  const auto pair_difference = [](const Fidus::RunSummary &a,
                                  const Fidus::RunSummary &b) {
    double difference = 0.;
    for (unsigned int p = 0; p < 2; ++p)
      difference =
        std::max({difference,
                  std::abs(a.omegas[p][2] - b.omegas[p][2]),
                  std::abs(a.velocities[p][0] - b.velocities[p][0]) / 0.05,
                  std::abs(a.velocities[p][1] - b.velocities[p][1]) / 0.05});
    return difference;
  };
  const auto with    = pair(true);
  const auto without = pair(false);
  check_range("pair: |omega| and |U|/a with minus without the rigid-body "
              "correction (shear rate 1)",
              pair_difference(with, without),
              0.,
              1e-5);
  // The matrix-free velocity block (with the boundary values' load from the
  // operator, not the assembly) is the same system as the assembled one:
  // the answers agree to the linear tolerance, with the boundary velocity
  // on every face (linear shear) and with periodic faces (sliding walls,
  // hanging nodes on the periodic faces: the pair sits across x = 0).
  check_range("pair, linear shear: |omega| and |U|/a, matrix-free minus "
              "assembled velocity block",
              pair_difference(with, pair(true, false)),
              0.,
              1e-7);
  check_range("pair, sliding walls: |omega| and |U|/a, matrix-free minus "
              "assembled velocity block",
              pair_difference(
                pair(true, true, "sliding walls", "0.951, 0.51; 0.049, 0.49"),
                pair(true, false, "sliding walls", "0.951, 0.51; 0.049, 0.49")),
              0.,
              1e-7);

  const auto three    = run(3, 4, "GMG");
  const auto three_ml = run(3, 4, "AMG");
  check_range("3D level 4: GMG L2 error of u / AMG L2 error of u",
              three.u_l2_error / three_ml.u_l2_error,
              0.999,
              1.001);
  return exit_code();
}
