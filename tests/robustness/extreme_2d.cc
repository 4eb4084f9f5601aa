// Stress tests on the seed paper's 2D pair: each must run without NaN and
// without any gap below -tolerance (walls included), with bounded solver
// iterations:
//  - penalty factor 1e6 (the solid 1e6 times more viscous than the fluid),
//    with the direct solver (the 2D default, as every case here) and FGMRES;
//  - a time step ten times the scene's default (1 instead of 0.1), with
//    'gluey' and 'inelastic';
//  - two particles 1e-12 apart and two particles touching the walls.

#include "../fidus_test.h"
#include "stress_tools.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

const double a   = 0.05;
const double tol = 1e-9 * a;

Fidus::RunSummary
run(const std::string &name,
    const std::string &model,
    const std::string &positions,
    const double       penalty,
    const double       dt,
    const double       end,
    const unsigned int level,
    const std::string &method = "auto")
{
  std::ostringstream prm;
  prm << "set Dimension = 2\n"
      << "set Output directory = " << name << "\n"
      << "subsection Fluid\n  set Penalty factor = " << penalty << "\n"
      << "  set Rigidity tolerance = 5e-3\n"
         "  set Rigidity measure = box\n"
      << "  set Maximum Uzawa iterations = 20\n"
      << "  subsection Linear solver\n    set Method = " << method
      << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = " << a << "\n"
      << "  set Positions = " << positions << "\nend\n"
      << "subsection Contact\n  set Model = " << model << "\nend\n"
      << "subsection Time stepping\n  set End time = " << end << "\n"
      << "  set Time step = " << dt << "\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

void
check(const std::string       &what,
      const Fidus::RunSummary &s,
      const bool               iterative = false)
{
  check_range(what + ": finite state", finite_state(s), 1, 1);
  check_range(what + ": minimum gap", s.min_gap, -tol, 1.);
  // One Uzawa iteration in every case (measured, commit 256e7ce): the
  // first solve already meets the rigidity tolerance; the cap is 20.
  check_range(what + ": largest Uzawa iterations",
              s.max_uzawa_iterations,
              1,
              2);
  // Per step, summed over the Uzawa iterations; none with the direct
  // solver, the 2D default, whose residual is checked at every solve.
  // With FGMRES at penalty 1e6 the cheap solve uses its 1000 iterations
  // and the expensive one finishes in 1 (1001 measured): the bound says
  // the fallback works, far below the cap of 20 x 2000.
  check_range(what + ": FGMRES iterations per step",
              s.max_linear_iterations,
              iterative ? 1 : 0,
              iterative ? 1200 : 0);
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const std::string pair = "0.451, 0.51; 0.549, 0.49";
  check("penalty 1e6", run("penalty", "gluey", pair, 1e6, 0.1, 0.2, 5));
  check("penalty 1e6, FGMRES",
        run("penalty_fgmres", "gluey", pair, 1e6, 0.1, 0.2, 5, "iterative"),
        true);
  for (const std::string model : {"gluey", "inelastic"})
    check("time step 1, " + model,
          run("dt_" + model, model, pair, 1e3, 1., 6., 5));
  // Gap 1e-12 between the first two; the others touch y = 0 and y = 1.
  check("1e-12 apart, touching walls",
        run("touching",
            "gluey",
            "0.45, 0.5; 0.550000000001, 0.5; 0.3, 0.05; 0.7, 0.95",
            1e3,
            0.1,
            0.5,
            6));
  return exit_code();
}
