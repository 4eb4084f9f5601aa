// The seed paper's 2D pair through the whole program (fictitious-domain
// fluid, AB2, contact projection), coarse and short: with 'none' the
// particles overlap (normalised distance below 1); with 'inelastic' and
// 'gluey' they never come closer than 1 - tolerance. The same run on 1 and
// 2 MPI ranks prints the same positions (files .output and .mpirun=2.output).
// Shared cells are held rigid, as in the seed's model and its prm.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

Fidus::RunSummary
run(const std::string &model)
{
  std::ostringstream prm;
  prm
    << "set Dimension = 2\n"
    << "set Output directory = output_" << model
    << "\n"
    // Solid retraction 0: the seed paper's model.
    << "subsection Fluid\n  set Solid retraction = 0\n  set Rigidity tolerance = 1e-3\n"
       "  set Rigidity measure = box\n"
    << "  set Shared cells = rigid\nend\n" // the seed's model
    << "subsection Particles\n  set Radius = 0.05\n"
    << "  set Positions = 0.451, 0.51; 0.549, 0.49\nend\n"
    << "subsection Contact\n  set Model = " << model << "\nend\n"
    << "subsection Time stepping\n  set End time = 1\n"
    << "  set Time step = 0.1\nend\n"
    << "subsection Mesh refinement\n"
    << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
    << "  set Maximum level = 6\nend\n"
    << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const double            tol  = 1e-9 * 0.05 / 0.1; // contact tolerance / (2a)
  const Fidus::RunSummary none = run("none");
  check_range("none: minimum normalised distance",
              none.min_normalised_distance,
              0.,
              0.9999);
  for (const std::string model : {"inelastic", "gluey"})
    {
      const Fidus::RunSummary s = run(model);
      check_range(model + ": minimum normalised distance",
                  s.min_normalised_distance,
                  1. - 2 * tol,
                  2.);
      if (model == "gluey")
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int d = 0; d < 2; ++d)
            print_value("gluey: particle " + std::to_string(i) +
                          " coordinate " + std::to_string(d) + " at t = 1",
                        s.positions[i][d],
                        5);
    }
  return exit_code();
}
