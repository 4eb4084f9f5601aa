// The stress of a dense 3D suspension does not depend on the penalty
// factor once the Uzawa loop has made the solid rigid: the bulk scenes
// (prm/rheology_bulk_3d*.prm) run at r = 300, or 100 with the accelerated
// Uzawa loop, instead of fidus's default 1000 because their velocity
// V-cycle weakens with r, and this is what makes that choice free. 48 spheres
// of radius 0.1 at phi = 0.2 in the unit cube between sliding walls (periodic
// in x and z), maximum level 4, released shared cells, inelastic contact, the
// solve of step 0 with the Uzawa loop to 1e-3 (box measure) and the linear
// solver to 1e-8, at r = 300 and 1000, and at r = 100 with Uzawa acceleration
// depth 3.
//
// The hydrodynamic stress holds the solid's penalised viscous stress
// r eta e(u) and the multiplier's; only their sum is fixed by rigidity,
// and the strain left in the solid (1e-3 of the box's) times r is of the
// order of the stress itself, so a stress that weighted either part
// wrongly would move with r by a large share of eta_r - 1 (0.26 here).
// Checked: every solve's rigidity residual below the tolerance; the
// relative viscosity at r = 300 (and 100) against r = 1000 within 1 % of
// eta_r - 1, N1 and the particle pressure within 2e-3 of eta_r (measured
// 0.15 %, 7e-5 and 1e-5 at r = 300; 0.52 %, 1e-5 and 1e-4 at r = 100
// with the accelerated loop).

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>
#include <utility>
#include <vector>

using namespace FidusTest;

namespace
{
  Fidus::RunSummary
  run(const double penalty, const unsigned int acceleration_depth = 0)
  {
    std::ostringstream prm;
    prm << "set Dimension = 3\nset Output directory = run_output\n"
        << "subsection Domain\n  set Lower left = 0, 0, 0\n"
        << "  set Upper right = 1, 1, 1\n"
        << "  set Boundary condition = sliding walls\nend\n"
        << "subsection Fluid\n  set Lubrication correction = true\n"
        << "  set Penalty factor = " << penalty << "\n"
        << "  set Rigidity tolerance = 1e-3\n  set Rigidity measure = box\n"
        << "  set Maximum Uzawa iterations = 40\n"
        << "  set Uzawa acceleration depth = " << acceleration_depth << "\n"
        << "  subsection Linear solver\n    set Tolerance = 1e-8\n  end\nend\n"
        << "subsection Particles\n  subsection Generator\n"
        << "    set Fraction = 0.2\n    set Radii = 0.1\n"
        << "    set Minimum separation = 0.01\n    set Seed = 3\n  end\nend\n"
        << "subsection Contact\n  set Model = inelastic\nend\n"
        << "subsection Time stepping\n  set End time = 0\n"
        << "  set Time step = 0.02\nend\n"
        << "subsection Mesh refinement\n  set Maximum level = 4\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const auto reference = run(1000.);
  const auto eta       = reference.stress.relative_viscosity;
  print_value("relative viscosity at r = 1000", eta, 3);
  check_range("largest rigidity residual at r = 1000 / tolerance",
              reference.max_rigidity_residual / 1e-3,
              0.,
              1.);
  // r = 100 with the accelerated loop: prm/rheology_bulk_3d.prm's setting.
  for (const auto &[r, depth] :
       std::vector<std::pair<double, unsigned int>>{{300., 0}, {100., 3}})
    {
      const auto        s = run(r, depth);
      const std::string at =
        " at r = " + std::to_string(static_cast<int>(r)) +
        (depth > 0 ? ", Anderson depth " + std::to_string(depth) :
                     std::string());
      check_range("largest rigidity residual" + at + " / tolerance",
                  s.max_rigidity_residual / 1e-3,
                  0.,
                  1.);
      check_range("|eta_r - eta_r(1000)| / (eta_r(1000) - 1)" + at,
                  std::abs(s.stress.relative_viscosity - eta) / (eta - 1.),
                  0.,
                  0.01);
      check_range("|N1 - N1(1000)| / eta_r(1000)" + at,
                  std::abs(s.stress.normal_stress_difference_1 -
                           reference.stress.normal_stress_difference_1) /
                    eta,
                  0.,
                  2e-3);
      check_range("|Pi - Pi(1000)| / eta_r(1000)" + at,
                  std::abs(s.stress.particle_pressure -
                           reference.stress.particle_pressure) /
                    eta,
                  0.,
                  2e-3);
    }
  return exit_code();
}
