// The lubrication correction moves the positions explicitly, so a gap that
// the corrected velocities close in less than one time step crosses zero,
// and with Contact/Model = none nothing stops the pair there
// (doc/lubrication.md, "Stability"). The program must say so.
//
// Two spheres (a = 0.05, gap 0.04 a) in the undisturbed shear flow, their
// line of centres on the compressive side, lubrication on (normal squeeze
// and tangential terms), no contact model: one step of 2 takes the gap
// past zero, steps of 0.5 do not. Checks:
// - time step 2: the warning "cannot hold the gap" is written, and the
//   run's smallest gap is negative and equal to the gap the warning
//   predicted for the end of the step: the warning and the overlap go
//   together;
// - time step 0.5 over the same time: no warning, and the gap stays
//   positive.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <fstream>
#include <iterator>

using namespace FidusTest;

namespace
{
  Fidus::RunSummary
  run(const double dt)
  {
    std::ostringstream prm;
    prm << "set Dimension = 3\nset Output directory = run_output\n"
        << "subsection Domain\n  set Lower left = 0, 0, 0\n"
        << "  set Upper right = 1, 1, 1\nend\n"
        << "subsection Fluid\n  set Model = undisturbed shear\n"
        << "  set Lubrication correction = true\nend\n"
        << "subsection Mesh refinement\n  set Maximum level = 5\nend\n"
        << "subsection Particles\n  set Radius = 0.05\n"
        << "  set Positions = 0.45, 0.51, 0.5; 0.55, 0.49, 0.5\nend\n"
        << "subsection Contact\n  set Model = none\n  set Roughness = 0\nend\n"
        << "subsection Time stepping\n  set End time = 2\n"
        << "  set Time step = " << dt << "\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }

  /// The number after " to " in the last line of warnings.txt that
  /// contains @p text (the gap the warning predicts).
  double
  predicted_gap(const std::string &text)
  {
    std::cerr.flush();
    std::ifstream in("warnings.txt");
    std::string   line, last;
    while (std::getline(in, line))
      if (line.find(text) != std::string::npos)
        last = line;
    const std::size_t k = last.find(" to ");
    return k == std::string::npos ? std::nan("") :
                                    std::stod(last.substr(k + 4));
  }

  /// How often @p text occurs in warnings.txt so far.
  unsigned int
  warnings_containing(const std::string &text)
  {
    std::cerr.flush();
    std::ifstream     in("warnings.txt");
    const std::string all((std::istreambuf_iterator<char>(in)),
                          std::istreambuf_iterator<char>());
    unsigned int      count = 0;
    for (std::size_t k = all.find(text); k != std::string::npos;
         k             = all.find(text, k + 1))
      ++count;
    return count;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  const std::string text = "cannot hold the gap";

  const auto large = run(2.);
  check_range("time step 2: warnings that the gap cannot be held",
              warnings_containing(text),
              1,
              1);
  check_range("time step 2: smallest gap / a", large.min_gap / 0.05, -10., 0.);
  check_range("time step 2: |smallest gap - predicted gap| / |smallest gap|",
              std::abs(large.min_gap - predicted_gap(text)) /
                std::abs(large.min_gap),
              0.,
              1e-4);

  const auto small = run(0.5);
  check_range("time step 0.5: new warnings that the gap cannot be held",
              warnings_containing(text) - 1.,
              0,
              0);
  check_range("time step 0.5: smallest gap / a",
              small.min_gap / 0.05,
              1e-4,
              0.04);
  return exit_code();
}
