// A run resumed from the checkpoint written just after a contact projection
// that stopped short of its tolerance continues as the uninterrupted run.
// Such a projection leaves overlaps of up to its residual, and the next one
// accepts up to twice that residual in its input (contact/carried_overlap);
// that bound is part of the run's state, so it must be in the checkpoint,
// or the resumed run's first projection refuses the overlap as broken input.
//
// Scene: three discs (a = 0.1) in a row in undisturbed shear at rate 0, the
// outer two pushed towards the middle one by external forces, inelastic
// contact, Contact/Maximum iterations = 1: one Gauss-Seidel sweep over the
// two coupled contacts cannot satisfy both, so every projection stops
// short and overlaps remain. The run to t = 0.3 (3 steps, a checkpoint at
// each), resumed to t = 0.6, against the run to t = 0.6 in one go:
// - the first part stops short in every step, and the overlap at the
//   checkpoint is beyond what a first projection accepts (2 x
//   Contact/Tolerance), so the resume exercises the carried bound;
// - the resumed run finishes, with the same final positions and minimum
//   gap as the uninterrupted run, to the last bit (one rank, same steps).

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/checkpoint.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

using namespace FidusTest;

namespace
{
  const double a = 0.1;

  Fidus::Parameters
  scene(const std::string &dir, const double end)
  {
    std::ostringstream prm;
    prm << "set Dimension = 2\nset Output directory = " << dir << "\n"
        << "subsection Domain\n  set Boundary condition = linear shear\n"
        << "  set Shear rate = 0\nend\n"
        << "subsection Fluid\n  set Model = undisturbed shear\nend\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = 0.29, 0.5; 0.5, 0.5; 0.71, 0.5\n"
        << "  set External force = 5, 0; 0, 0; -5, 0\nend\n"
        << "subsection Contact\n  set Model = inelastic\n"
        << "  set Maximum iterations = 1\nend\n"
        << "subsection Time stepping\n  set End time = " << end << "\n"
        << "  set Time step = 0.1\nend\n"
        << "subsection Output\n  set Verbosity = quiet\n"
        << "  set Checkpoint interval = 1\nend\n";
    return Fidus::read_parameters_from_string(prm.str());
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const auto whole = Fidus::run_simulation(scene("whole", 0.6));
  const auto first = Fidus::run_simulation(scene("parts", 0.3));
  check_range("first part: projections that stopped short",
              first.contact_failures,
              3,
              3);
  check_range("first part: overlap at the checkpoint / (2 x tolerance)",
              -first.min_gap / (2. * 1e-9 * a),
              10.,
              1e12);

  const Fidus::Parameters resumed_prm = scene("parts", 0.6);
  const auto point  = Fidus::Checkpoint::find_and_check(resumed_prm);
  const auto second = Fidus::run_simulation(resumed_prm, &point);
  check_range("resumed: steps", second.n_steps, 6, 6);
  double largest = 0.;
  for (std::size_t i = 0; i < whole.positions.size(); ++i)
    for (unsigned int d = 0; d < 3; ++d)
      largest =
        std::max(largest,
                 std::abs(whole.positions[i][d] - second.positions[i][d]));
  check_range("resumed against uninterrupted: largest |dX| / a",
              largest / a,
              0.,
              0.);
  check_range("resumed against uninterrupted: min gap difference / a",
              std::abs(whole.min_gap - second.min_gap) / a,
              0.,
              0.);
  return exit_code();
}
