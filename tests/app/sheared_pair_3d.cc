// The closest approach of the seed paper's 3D pair with the sub-grid
// lubrication correction, a coarse and short version of
// doc/history/lubrication_sheared_pair.md ("Two spheres passing in shear
// against Batchelor & Green"). Two spheres (a = 0.05) in linear shear start
// where Batchelor & Green's exact passage of prm/two_particles_3d.prm is at t =
// 6 (relative position (1.096, -0.5945) x 2a, from
// contrib/benchmarks/batchelor_green.py), and are sheared for 3 time units,
// through the closest approach (exact: gap 7.37e-3 a, 1.89 into this run).
// Maximum level 5 (a/h = 1.6), released shared cells with the correction
// (retraction 0), inelastic contact,
// steps of 0.1.
// - After the solve (Lubrication coupling; auto would solve this dilute
//   pair with the flow), the smallest gap is between 0.4 and 2 times the
//   exact one: 0.44 with
//   the 3D flow range's ramp (Lubrication flow edge), 0.35 with the step
//   it replaced, 0.14 without the correction, all outside at the lower
//   end but the first. Level 5 is coarser than the level 6 on which the
//   ramp was fitted, and the default roughness (5e-3 a) caps the
//   resistance just below the exact gap.
// - The correction acted, and the pair passes: at the end the second
//   sphere, which started downstream, is upstream of the first.
// - Solved with the flow (Lubrication coupling), the smallest gap is
//   between 0.5 and 2 times the exact one (measured 0.68), and larger
//   than after the solve.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <sstream>

using namespace FidusTest;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const double a = 0.05, exact_gap = 7.37e-3 * a;
  const auto   run = [&](const std::string &fluid_entries,
                       const double       end_time) {
    std::ostringstream prm;
    prm << "set Dimension = 3\nset Output directory = run_output\n"
        << "subsection Domain\n  set Lower left = 0, 0, 0\n"
        << "  set Upper right = 1, 1, 1\n"
        << "  set Boundary condition = linear shear\n"
        << "  set Shear rate = 1\nend\n"
        << "subsection Fluid\n  set Lubrication correction = true\n"
        << "  set Solid retraction = 0\n"
        << "  set Rigidity tolerance = 1e-3\n  set Rigidity measure = box\n"
        << fluid_entries << "end\n"
        << "subsection Particles\n  set Radius = " << a << "\n"
        << "  set Positions = 0.4452, 0.529726, 0.5; 0.5548, 0.470274, 0.5\n"
        << "end\n"
        << "subsection Contact\n  set Model = inelastic\nend\n"
        << "subsection Time stepping\n  set End time = " << end_time << "\n"
        << "  set Time step = 0.1\nend\n"
        << "subsection Mesh refinement\n  set Maximum level = 5\nend\n"
        << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  };
  const auto s = run("  set Lubrication coupling = after the solve\n", 3.);
  check_range("smallest gap / exact smallest gap (Batchelor & Green)",
              s.min_gap / exact_gap,
              0.4,
              2.);
  check_range("the pair passes: x1 - x0 at the end, over 2a",
              (s.positions[1][0] - s.positions[0][0]) / (2. * a),
              -10.,
              -0.1);

  // Solved with the flow (the bonds' loads in the fluid solve), through
  // the closest approach only (at t = 1.3 here): measured 0.68 of the
  // exact gap, where the correction after the solve gives 0.44; at the
  // production settings 0.59 against 0.07-0.21 (doc/validation.md).
  const auto coupled = run("  set Lubrication coupling = with the flow\n", 1.8);
  check_range("with the flow: smallest gap / exact smallest gap",
              coupled.min_gap / exact_gap,
              0.5,
              2.);
  check_range("with the flow / after the solve: smallest gap",
              coupled.min_gap / s.min_gap,
              1.2,
              10.);
  return exit_code();
}
