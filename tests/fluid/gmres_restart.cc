// Fluid/Linear solver/GMRES restart reaches the fictitious domain's FGMRES:
// a 2D pair solved with the AMG (Method = iterative) to the linear
// tolerance 1e-9, once with the default 200 and once restarting every 10
// iterations. Checks:
// - the solve with the default needs more than 10 iterations, so the small
//   restart must act;
// - restarting every 10 iterations needs more iterations than the default
//   (a restarted FGMRES loses its Krylov basis; if the entry did nothing
//   the counts would be equal);
// - both give the same particle velocities, below 1e-6 (gamma_dot a units):
//   each solved the same system to 1e-9.

#include "../fidus_test.h"
#include "summary_tools.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int restart)
{
  std::ostringstream prm;
  prm << "set Dimension = 2\nset Output directory = run_output\n"
      << "subsection Fluid\n  set Maximum Uzawa iterations = 2\n"
      << "  subsection Linear solver\n    set Method = iterative\n"
      << "    set Tolerance = 1e-9\n    set GMRES restart = " << restart
      << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = 0.1\n"
      << "  set Positions = 0.35, 0.52; 0.62, 0.47\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n  set Maximum level = 6\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const Fidus::RunSummary full      = run(200);
  const Fidus::RunSummary restarted = run(10);
  check_range("FGMRES iterations of a solve with GMRES restart = 200, > 10",
              full.max_linear_iterations,
              11,
              1000);
  check_range("FGMRES iterations, restart 10 minus restart 200, > 0",
              double(restarted.max_linear_iterations) -
                double(full.max_linear_iterations),
              1,
              100000);
  check_range("|dU|/a, |d omega|, restart 10 minus restart 200",
              difference(restarted, full, 0.1),
              0.,
              1e-6);
  return exit_code();
}
