// Fluid/Linear solver/Memory per rank: the fictitious domain's iterative
// solvers checked against a memory budget. One sphere in 3D with the
// matrix-free GMG at level 4, solved at step 0:
// - auto, GMRES restart 200: the restart is kept (the basis of a few
//   thousand unknowns fits on any machine that runs the test suite);
// - a budget of 2 GB per rank with GMRES restart = 1000000: that basis would
//   need two vectors of the system per iteration, far more than 2 GB, so
//   the restart used must be lowered to at most (2 GB / (8 bytes x
//   unknowns) - 3) / 2 and stay >= 10, and the velocities must be those of
//   the first run (both solves converge long before either restart);
// - a budget of 1 MB per rank, below what the process already holds: the
//   run must stop before the system is built, with a RunError that names
//   the entries to change.

#include "../fidus_test.h"
#include "summary_tools.h"

#include <fidus/core/input_error.h>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int restart, const std::string &memory)
{
  std::ostringstream prm;
  prm
    << "set Dimension = 3\nset Output directory = run_output\n"
    << "subsection Domain\n  set Lower left = 0, 0, 0\n"
    << "  set Upper right = 1, 1, 1\nend\n"
    // Solid retraction 0: the seed's model, in which the bounds below were
    // measured.
    << "subsection Fluid\n  set Solid retraction = 0\n  subsection Linear solver\n"
    << "    set Method = iterative\n    set Preconditioner = GMG\n"
    << "    set GMRES restart = " << restart
    << "\n    set Memory per rank = " << memory << "\n  end\nend\n"
    << "subsection Particles\n  set Radius = 0.2\n"
    << "  set Positions = 0.52, 0.47, 0.5\nend\n"
    << "subsection Time stepping\n  set End time = 0\nend\n"
    << "subsection Mesh refinement\n  set Maximum level = 4\nend\n"
    << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const Fidus::RunSummary free_run = run(200, "auto");
  check_range("GMRES restart used with Memory per rank = auto",
              free_run.smallest_gmres_restart,
              200,
              200);

  const Fidus::RunSummary budget = run(1000000, "2");
  const double bound = (2e9 / (8. * double(budget.n_dofs)) - 3.) / 2.;
  check_range("GMRES restart used with 2 GB per rank, in [10, "
              "(2 GB / (8 unknowns) - 3) / 2]",
              budget.smallest_gmres_restart,
              10,
              bound);
  check_range("|dU|/a, |d omega|, 2 GB budget minus auto",
              difference(budget, free_run, 0.2),
              0.,
              1e-8);

  bool        stopped = false;
  std::string message;
  try
    {
      run(200, "0.001");
    }
  catch (const Fidus::RunError &e)
    {
      stopped = true;
      message = e.what();
    }
  check_range("a budget of 1 MB per rank stops the run (1: it did)",
              stopped,
              1,
              1);
  check_range("its message names 'Maximum level' and 'Memory per rank' "
              "(1: it does)",
              message.find("Mesh refinement/Maximum level") !=
                  std::string::npos &&
                message.find("Memory per rank") != std::string::npos,
              1,
              1);
  return exit_code();
}
