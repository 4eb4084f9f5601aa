// The cut finite element on the exact rigid inclusion (CutStokesInclusion,
// 2D, a = 0.1, three positions off the mesh's symmetry, two band levels
// around the particle):
//
// - the rigid velocity converges with refinement, with no floor: the omega
//   error is below 1e-6 at level 7 (h = a / 12.8; the fictitious-domain
//   predictor stalls near 1e-4 there, doc/uzawa.md) and falls at an observed
//   order of at least 2.5 from level 5 to level 7, and |U| / (g a) is below
//   2e-6;
// - a particle whose surface lies 1e-10 beyond a grid line (fluid slivers of
//   relative size 1e-8 in the cut cells) is solved as accurately, thanks to
//   the ghost penalties;
// - a non-positive radius is refused.

#include "../fidus_test.h"

#include <algorithm>
#include <cmath>
#include <fidus/fluid/cut_stokes_inclusion.h>
#include <stdexcept>

using namespace FidusTest;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using Solver                                = Fidus::CutStokesInclusion<2>;
  const std::vector<dealii::Point<2>> centers = {{0.5132, 0.4871},
                                                 {0.4417, 0.5523},
                                                 {0.5609, 0.4288}};
  std::vector<double>                 omega(3, 0.), translation(3, 0.);
  for (unsigned int k = 0; k < 3; ++k)
    for (const auto &c : centers)
      {
        Solver::Settings s;
        s.center       = c;
        s.radius       = 0.1;
        s.global_level = 3 + k;
        s.band_levels  = 2;
        const auto r   = Solver::solve(s);
        omega[k]       = std::max(omega[k], r.omega_error);
        translation[k] = std::max(translation[k], r.translation);
      }
  check_range("level 7: largest relative omega error", omega[2], 0., 1e-6);
  check_range("level 7: largest |U| / (g a)", translation[2], 0., 2e-6);
  check_range("observed order of the omega error, levels 5 to 7",
              std::log2(omega[0] / omega[2]) / 2.,
              2.5,
              10.);

  Solver::Settings sliver;
  sliver.center       = dealii::Point<2>(0.5 + 1e-10, 0.5 + 1e-10);
  sliver.radius       = 0.125;
  sliver.global_level = 4;
  sliver.band_levels  = 2;
  const auto r        = Solver::solve(sliver);
  check_range("surface 1e-10 beyond a grid line: relative omega error",
              r.omega_error,
              0.,
              1e-5);
  check_range("surface 1e-10 beyond a grid line: |U| / (g a)",
              r.translation,
              0.,
              1e-5);

  bool refused = false;
  try
    {
      Solver::Settings bad;
      bad.center = dealii::Point<2>(0.5, 0.5);
      bad.radius = 0.;
      Solver::solve(bad);
    }
  catch (const std::invalid_argument &)
    {
      refused = true;
    }
  check_range("a radius of 0 refused", refused ? 1. : 0., 1., 1.);
  return exit_code();
}
