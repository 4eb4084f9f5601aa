// The paper's 2D pair through the cut finite element in the time loop
// (Fluid/Model = cut finite element): the fluid lives outside the
// particles only, and a mesh is built for every solve (doc/cut_element.md,
// "In the time loop").
//
// - The scene is point-symmetric about the box centre (the pair at
//   (0.451, 0.51) and (0.549, 0.49), the box's linear shear), and so is
//   every mesh built for it: X_0 + X_1 stays (1, 1), to the accuracy of
//   the cut quadratures.
// - The contact model keeps working on top: 'inelastic' holds the pair at
//   a gap >= 0 where the time step's error would let it overlap
//   (doc/cut_element.md, "A rolling pair and the time step").
// - Two levels agree: the trajectories of levels 5 and 6 differ by far
//   less than the 1 % of a diameter that fixes the fictitious domain's
//   shipped level.
// - The stress output: one disc in the middle of the box, area fraction
//   phi = pi a^2, has the relative viscosity of dilute discs, 1 + 2 phi,
//   up to the box's walls, whose share falls like a^2: within 2 % of 2 phi
//   at a = 0.025, and four times that at a = 0.05.
// - Between sliding walls (periodic in x), a disc crosses the periodic
//   face at the speed of the shear; the scene shifted by half the period
//   moves the same way, to the discretisation error: its meshes are the
//   translates of the first scene's but for the cells refined to match
//   the periodic faces (4e-6 a measured after 3 steps, where levels 5 and
//   6 differ by 5e-4 a over 10 steps); the walls' shear stress equals the
//   volume average's, an identity of the discrete solution up to the cut
//   quadratures' error (doc/cut_element.md, "Periodic faces").
// - Fluid/Cut linear solver = iterative gives the direct solver's
//   trajectory, and its FGMRES iterations reach statistics.csv.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

const double x0[2][2] = {{0.451, 0.51}, {0.549, 0.49}};
const double radius   = 0.05;

Fidus::RunSummary
run(const std::string &name,
    const double       end_time,
    const unsigned int level,
    const std::string &positions = "",
    const double       a         = radius,
    const std::string &boundary  = "linear shear",
    const std::string &fluid     = "")
{
  std::ostringstream prm;
  prm << "set Dimension = 2\n"
      << "set Output directory = " << name << "\n"
      << "subsection Domain\n  set Boundary condition = " << boundary
      << "\nend\n"
      << "subsection Fluid\n  set Model = cut finite element\n"
      << "  set Cut minimum gap = 1e-3\n"
      << fluid << "end\n"
      << "subsection Particles\n  set Radius = " << a << "\n"
      << "  set Positions = ";
  if (positions.empty())
    prm << x0[0][0] << ", " << x0[0][1] << "; " << x0[1][0] << ", " << x0[1][1];
  else
    prm << positions;
  prm << "\nend\n"
      << "subsection Contact\n  set Model = inelastic\nend\n"
      << "subsection Time stepping\n  set End time = " << end_time << "\n"
      << "  set Time step = 0.2\n  set Scheme = trapezoidal\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 3\n  set Minimum level = 3\n"
      << "  set Maximum level = " << level << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

/// Largest distance between the same particle in two runs, over radius.
double
distance(const Fidus::RunSummary &a, const Fidus::RunSummary &b)
{
  double d = 0.;
  for (unsigned int i = 0; i < a.positions.size(); ++i)
    d = std::max(d,
                 std::hypot(a.positions[i][0] - b.positions[i][0],
                            a.positions[i][1] - b.positions[i][1]) /
                   radius);
  return d;
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const Fidus::RunSummary forward = run("level_5", 2., 5);
  check_range("level 5, t = 2: |X_0 + X_1 - (1, 1)| / a",
              std::hypot(forward.positions[0][0] + forward.positions[1][0] - 1.,
                         forward.positions[0][1] + forward.positions[1][1] -
                           1.) /
                radius,
              0.,
              1e-6);
  check_range("level 5, inelastic: smallest gap / a",
              forward.min_gap / radius,
              -1e-8,
              1.);
  check_range("level 5: the pair moved, |X(2) - X(0)| / a",
              std::hypot(forward.positions[0][0] - x0[0][0],
                         forward.positions[0][1] - x0[0][1]) /
                radius,
              0.05,
              10.);

  // One disc in the middle of the box, its radius 3.2 cells of the finest
  // level: (eta_r - 1) / (2 phi) tends to 1 as the box's walls recede,
  // their correction falling like a^2.
  const auto excess = [](const double a, const unsigned int level) {
    const double phi = M_PI * a * a;
    return (run("one_disc_" + std::to_string(level), 0., level, "0.5, 0.5", a)
              .stress.relative_viscosity -
            1.) /
             (2. * phi) -
           1.;
  };
  const double wide = excess(0.05, 6), narrow = excess(0.025, 7);
  check_range("one disc, a = 0.025: (relative viscosity - 1) / (2 phi) - 1",
              narrow,
              -0.02,
              0.02);
  check_range("one disc: wall excess at a = 0.05 over that at a = 0.025",
              wide / narrow,
              3.,
              5.);

  // Three discs between sliding walls, one of them crossing the periodic
  // face at x = 1, and the same scene shifted by half the period.
  const std::string       walls   = "sliding walls";
  const Fidus::RunSummary sliding = run("sliding",
                                        0.6,
                                        5,
                                        "0.98, 0.8; 0.52, 0.5; 0.3, 0.25",
                                        radius,
                                        walls),
                          shifted = run("sliding_shifted",
                                        0.6,
                                        5,
                                        "0.48, 0.8; 0.02, 0.5; 0.8, 0.25",
                                        radius,
                                        walls);
  check_range("sliding walls: the disc that crossed x = 1, its x-distance "
              "travelled over that of the undisturbed flow, 0.3 t",
              (sliding.positions[0][0] + 1. - 0.98) / (0.3 * 0.6),
              0.9,
              1.1);
  double shift = 0.;
  for (unsigned int i = 0; i < 3; ++i)
    {
      double dx = shifted.positions[i][0] - sliding.positions[i][0] - 0.5;
      dx -= std::round(dx);
      shift =
        std::max(shift,
                 std::hypot(dx,
                            shifted.positions[i][1] - sliding.positions[i][1]) /
                   radius);
    }
  check_range("sliding walls: the scene shifted by half the period, "
              "largest |X - X_shifted| / a (modulo the period)",
              shift,
              0.,
              5e-5);
  check_range("sliding walls: the walls' shear stress against the volume "
              "average, relative difference over the particles' share",
              std::abs(sliding.stress.wall_shear_stress -
                       sliding.stress.hydrodynamic_shear_stress) /
                (sliding.stress.hydrodynamic_shear_stress - 1.),
              0.,
              1e-6);

  // Fluid/Cut linear solver: the iterative solver gives the direct one's
  // trajectory (both solve the same system, to 1e-10 and to round-off),
  // and its FGMRES iterations reach statistics.csv. The three discs
  // between sliding walls, whose gaps are wide: the paper's pair, 4e-4 a
  // apart, refines its gap to cells where the velocity AMG fails (FGMRES
  // stops at 2.5e-5 after 2000 iterations, reported; doc/cut_element.md).
  const auto with_solver = [&](const std::string &solver) {
    return run(solver,
               0.4,
               4,
               "0.98, 0.8; 0.52, 0.5; 0.3, 0.25",
               radius,
               walls,
               "  set Cut linear solver = " + solver + "\n");
  };
  const Fidus::RunSummary direct    = with_solver("direct"),
                          iterative = with_solver("iterative");
  check_range("Cut linear solver: iterative against direct, "
              "|X difference| / a at t = 0.4",
              distance(direct, iterative),
              0.,
              1e-7);
  // The smallest linear_iterations over the steps (the first row is the
  // initial state, before any solve).
  const auto iterations = [](const std::string &solver) {
    const auto column =
      csv_column(solver + "/statistics.csv", "linear_iterations");
    double smallest = 1e9;
    for (unsigned int k = 1; k < column.size(); ++k)
      smallest = std::min(smallest, column[k]);
    return smallest;
  };
  check_range("Cut linear solver = direct: linear_iterations 0",
              iterations("direct"),
              0.,
              0.);
  check_range("Cut linear solver = iterative: linear_iterations >= 1 at "
              "every step",
              iterations("iterative"),
              1.,
              1e4);

  const Fidus::RunSummary finer = run("level_6", 2., 6);
  check_range("t = 2: |X(level 5) - X(level 6)| / a",
              distance(forward, finer),
              0.,
              2e-3);
  return exit_code();
}
