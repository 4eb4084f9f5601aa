// Reversibility through the fictitious-domain fluid, the seed paper's
// claim. The paper's 2D pair is sheared to T = 3 (glued, turning as a
// doublet) and then by the reversed shear to 2T ('Shear rate = t < 3 ? 1 :
// -1'). Stokes flow is reversible, so a contact model that keeps that
// property brings every particle back to its start: with 'gluey' within 1 %
// of the radius. With 'inelastic' the non-penetration impulses of the
// forward half are not given back and the particles miss their start by
// more than that.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

const double x0[2][2] = {{0.451, 0.51}, {0.549, 0.49}};
const double radius   = 0.05;

/// Largest distance of a particle from its start at t = 2T, over radius.
double
return_miss(const std::string &model)
{
  std::ostringstream prm;
  prm << "set Dimension = 2\n"
      << "set Output directory = reversal_" << model << "\n"
      << "subsection Domain\n  set Shear rate = t < 3 ? 1 : -1\nend\n"
      << "subsection Fluid\n  set Rigidity tolerance = 5e-3\n"
         "  set Rigidity measure = box\n"
      << "  set Maximum Uzawa iterations = 4\nend\n"
      << "subsection Particles\n  set Radius = " << radius << "\n"
      << "  set Positions = " << x0[0][0] << ", " << x0[0][1] << "; "
      << x0[1][0] << ", " << x0[1][1] << "\nend\n"
      << "subsection Contact\n  set Model = " << model << "\nend\n"
      << "subsection Time stepping\n  set End time = 6\n"
      << "  set Time step = 0.1\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
      << "  set Maximum level = 5\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  const Fidus::RunSummary s =
    Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  double miss = 0;
  for (unsigned int i = 0; i < 2; ++i)
    miss = std::max(miss,
                    std::hypot(s.positions[i][0] - x0[i][0],
                               s.positions[i][1] - x0[i][1]) /
                      radius);
  return miss;
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  check_range("gluey: |X(2T) - X(0)| / a", return_miss("gluey"), 0., 0.01);
  check_range("inelastic: |X(2T) - X(0)| / a",
              return_miss("inelastic"),
              0.01,
              10.);
  return exit_code();
}
