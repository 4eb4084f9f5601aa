// How the Uzawa loop stops, on the exact rigid inclusion (2D, a = 0.05, off
// the mesh's symmetry, maximum level 7, linear tolerance 1e-10):
//
// - with Sliver threshold = 0.5 (cells with less than half of their
//   quadrature points in the solid held by the penalty alone) the loop
//   reaches a rigidity residual of 1e-6; the particle's velocity then stays
//   within the discretisation error of the exact one (omega = -g/2, U = 0)
//   and within it of the fully constrained solution;
// - with Rigid velocity tolerance = 1e-4 the loop stops once the rigid
//   velocity changed by less than that in one iteration; the velocity is
//   then within 1e-3 (ten tolerances) of the converged one above, and the
//   change it reports is below the tolerance;
// - with Inexact Uzawa factor = 1 (the solves inside the loop only to the
//   rigidity tolerance, the last one to the linear tolerance) the loop
//   reaches the same residual with fewer FGMRES iterations, and the
//   velocity is within ten rigidity tolerances of the exact solves' one;
// - with Uzawa acceleration depth = 3 (Anderson) the loop reaches 1e-6 in
//   fewer iterations than the plain one, at the same rigid velocity.

#include "../fidus_test.h"

#include <cmath>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>
#include <fstream>
#include <sstream>
#include <string>

using namespace FidusTest;

namespace
{
  Fidus::RunSummary
  run(const std::string &fluid_settings)
  {
    std::ostringstream prm;
    prm << "set Dimension = 2\n"
        << "set Output directory = run_output\n"
        << "subsection Domain\n"
        << "  set Boundary condition = exact rigid inclusion\n"
        << "end\n"
        // Solid retraction 0: the seed's model, in which the bounds below were
        // measured.
        << "subsection Fluid\n  set Solid retraction = 0\n"
        << "  set Maximum Uzawa iterations = 60\n"
        << fluid_settings
        // FGMRES: the inexact solves below only exist there.
        << "  subsection Linear solver\n    set Tolerance = 1e-10\n"
        << "    set Method = iterative\n  end\n"
        << "end\n"
        << "subsection Particles\n  set Radius = 0.05\n"
        << "  set Positions = 0.5132, 0.4871\nend\n"
        << "subsection Time stepping\n  set End time = 0\nend\n"
        << "subsection Mesh refinement\n"
        << "  set Initial global refinement = 2\n"
        << "  set Minimum level = 2\n"
        << "  set Maximum level = 7\nend\n"
        << "subsection Output\n  set Verbosity = quiet\n"
        << "  set Field output interval = 0\n"
        << "  set Particle output interval = 0\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }

  /// The last row's value of @p name in run_output/statistics.csv.
  double
  last_value(const std::string &name)
  {
    std::ifstream in("run_output/statistics.csv");
    std::string   header, line, last;
    std::getline(in, header);
    while (std::getline(in, line))
      if (!line.empty())
        last = line;
    std::istringstream h(header), l(last);
    std::string        key, value;
    while (std::getline(h, key, ',') && std::getline(l, value, ','))
      if (key == name)
        return std::stod(value);
    return std::nan("");
  }

  /// Largest difference of the rigid velocities of two runs, |dU| / (g a)
  /// and |d omega| / g (g = 1, a = 0.05).
  double
  difference(const Fidus::RunSummary &a, const Fidus::RunSummary &b)
  {
    double du = 0., dw = 0.;
    for (unsigned int d = 0; d < 3; ++d)
      {
        du += std::pow(a.velocities[0][d] - b.velocities[0][d], 2);
        dw += std::pow(a.omegas[0][d] - b.omegas[0][d], 2);
      }
    return std::max(std::sqrt(du) / 0.05, std::sqrt(dw));
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  // Every cell that meets the solid constrained, the default tolerance.
  const Fidus::RunSummary constrained = run("");

  const Fidus::RunSummary released = run("  set Rigidity tolerance = 1e-6\n"
                                         "  set Rigidity measure = box\n"
                                         "  set Sliver threshold = 0.5\n");
  const double            released_fgmres = last_value("linear_iterations");
  check_range("slivers released: steps whose Uzawa loop missed 1e-6",
              released.uzawa_failures,
              0,
              0);
  check_range("slivers released: rigidity residual",
              released.max_rigidity_residual,
              0.,
              1e-6);
  check_range("slivers released: relative omega error",
              released.omega_error,
              0.,
              5e-3);
  check_range("slivers released: |U| / (g a)",
              released.translation_error,
              0.,
              1.5e-2);
  check_range("slivers released against all constrained: rigid velocity "
              "difference",
              difference(released, constrained),
              0.,
              5e-3);

  const Fidus::RunSummary by_velocity =
    run("  set Rigid velocity tolerance = 1e-4\n"
        "  set Sliver threshold = 0.5\n");
  check_range("velocity stop: steps whose Uzawa loop missed it",
              by_velocity.uzawa_failures,
              0,
              0);
  check_range("velocity stop: last change of the rigid velocity",
              last_value("rigid_velocity_change"),
              0.,
              1e-4);
  check_range("velocity stop: Uzawa iterations / those to reach 1e-6",
              double(by_velocity.max_uzawa_iterations) /
                released.max_uzawa_iterations,
              0.,
              0.75);
  check_range("velocity stop: distance to the converged rigid velocity",
              difference(by_velocity, released),
              0.,
              1e-3);

  // The first solve is inexact only without Reuse multiplier.
  const Fidus::RunSummary inexact = run("  set Rigidity tolerance = 1e-6\n"
                                        "  set Rigidity measure = box\n"
                                        "  set Sliver threshold = 0.5\n"
                                        "  set Reuse multiplier = false\n"
                                        "  subsection Linear solver\n"
                                        "    set Inexact Uzawa factor = 1\n"
                                        "  end\n");
  check_range("inexact Uzawa: steps whose Uzawa loop missed 1e-6",
              inexact.uzawa_failures,
              0,
              0);
  check_range("inexact Uzawa: rigidity residual",
              inexact.max_rigidity_residual,
              0.,
              1e-6);
  check_range("inexact Uzawa: FGMRES iterations / those of exact solves",
              last_value("linear_iterations") / released_fgmres,
              0.,
              0.9);
  check_range("inexact Uzawa: distance to the exact solves' rigid velocity",
              difference(inexact, released),
              0.,
              1e-5);

  // Anderson acceleration: the same loop to 1e-6 as 'released', with the
  // last three iterates combined. The multiplier it converges to is the
  // same fixed point, so the velocity agrees with the plain loop's to the
  // tolerance's reach, in fewer iterations.
  const Fidus::RunSummary accelerated =
    run("  set Rigidity tolerance = 1e-6\n"
        "  set Rigidity measure = box\n"
        "  set Sliver threshold = 0.5\n"
        "  set Uzawa acceleration depth = 3\n");
  check_range("Anderson: steps whose Uzawa loop missed 1e-6",
              accelerated.uzawa_failures,
              0,
              0);
  check_range("Anderson: rigidity residual",
              accelerated.max_rigidity_residual,
              0.,
              1e-6);
  check_range("Anderson: Uzawa iterations / plain Uzawa's",
              double(accelerated.max_uzawa_iterations) /
                released.max_uzawa_iterations,
              0.,
              0.5);
  check_range("Anderson: distance to the plain loop's rigid velocity",
              difference(accelerated, released),
              0.,
              1e-5);
  return exit_code();
}
