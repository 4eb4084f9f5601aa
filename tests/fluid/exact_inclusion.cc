// Rigid inclusion with the exact solution on the boundary (validation.md
// case 3b), 2D and 3D: the L2 error of u on the fluid part decreases as the
// maximum refinement level increases, and omega is within 0.5 % of -g/2 at
// the finest level. The observed orders go to measured_values.txt.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <vector>

using namespace FidusTest;

Fidus::RunSummary
run(const unsigned int dim, const unsigned int level)
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
      << "  subsection Linear solver\n    set Tolerance = 1e-8\n  end\nend\n"
      << "subsection Particles\n  set Radius = " << (dim == 2 ? "0.15" : "0.2")
      << "\n  set Positions = " << (dim == 2 ? "0.5, 0.5" : "0.5, 0.5, 0.5")
      << "\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 2\n"
      << "  set Minimum level = 2\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

void
study(const unsigned int dim, const std::vector<unsigned int> &levels)
{
  std::vector<Fidus::RunSummary> s;
  for (const unsigned int l : levels)
    s.push_back(run(dim, l));
  const std::string name = std::to_string(dim) + "D";
  for (unsigned int k = 1; k < s.size(); ++k)
    {
      // Halving h at the surface: the ratio of errors gives the order.
      const double order = std::log2(s[k - 1].u_l2_error / s[k].u_l2_error);
      check_range(name + " level " + std::to_string(levels[k]) +
                    ": observed order of the L2 velocity error",
                  order,
                  0.5,
                  10.);
    }
  check_range(name + " finest: relative omega error",
              s.back().omega_error,
              0.,
              0.005);
  check_range(name + " finest: |U| / (g a)",
              s.back().translation_error,
              0.,
              0.005);
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  study(2, {5, 6, 7});
  study(3, {3, 4});
  return exit_code();
}
