// Stress test: a dense 2D suspension, 100 discs at area fraction 0.41
// between sliding walls (periodic in x).
//  - 'undisturbed shear' for 10 strain units (1000 steps) with 'gluey' and
//    with 'inelastic': particles cross the periodic faces many times and
//    meet in clusters; no gap may go below -tolerance, every projection
//    must converge, nothing may become NaN.
//  - the fictitious-domain fluid for 5 steps on the same layout (level 5,
//    with the direct solver and with FGMRES;
//    where many gaps are below the cell size): Uzawa and FGMRES
//    iterations within measured bounds, no NaN, no overlap, and particle
//    velocities that stay physical. A multiplier carried over from a loop
//    that did not converge used to grow from step to step and drove the
//    velocities to garbage (max |U| 0.90, max |omega| 19 after 5 steps).

#include "../fidus_test.h"
#include "stress_tools.h"

#include <algorithm>
#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

const double a   = 0.036;
const double tol = 1e-9 * a; // Contact/Tolerance (relative) times a

Fidus::RunSummary
run(const std::string &fluid,
    const std::string &model,
    const double       end,
    const std::string &method = "auto")
{
  const auto         x = random_layout(2, 100, a, 1e-3, 7);
  std::ostringstream prm;
  prm << "set Dimension = 2\n"
      << "set Output directory = dense_" << model << "_"
      << (fluid[0] == 'u' ? "undisturbed" : "fd") << "\n"
      << "subsection Domain\n  set Boundary condition = sliding walls\nend\n"
      // Solid retraction 0: the seed's model, in which the bounds below were
      // measured.
      << "subsection Fluid\n  set Solid retraction = 0\n  set Model = " << fluid
      << "\n"
      << "  set Rigidity tolerance = 1e-3\n"
         "  set Rigidity measure = box\n"
      << "  set Maximum Uzawa iterations = 3\n"
      << "  subsection Linear solver\n    set Method = " << method
      << "\n  end\nend\n"
      << "subsection Particles\n  set Radius = " << a << "\n"
      << "  set Positions = " << positions_entry(x, 2) << "\nend\n"
      << "subsection Contact\n  set Model = " << model << "\nend\n"
      << "subsection Time stepping\n  set End time = " << end << "\n"
      << "  set Time step = " << (fluid[0] == 'u' ? 0.01 : 0.02) << "\nend\n"
      << "subsection Mesh refinement\n"
      << "  set Initial global refinement = 4\n  set Minimum level = 4\n"
      << "  set Maximum level = " << (fluid[0] == 'u' ? 6 : 5) << "\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
  return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
}

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();
  for (const std::string model : {"gluey", "inelastic"})
    {
      const Fidus::RunSummary s = run("undisturbed shear", model, 10.);
      const std::string       w = "undisturbed, " + model + ": ";
      check_range(w + "steps", s.n_steps, 1000, 1000);
      check_range(w + "finite state", finite_state(s), 1, 1);
      check_range(w + "minimum gap", s.min_gap, -tol, 1.);
      check_range(w + "non-converged projections", s.contact_failures, 0, 0);
      check_range(w + "largest dual iterations",
                  s.max_contact_iterations,
                  0,
                  20000);
    }
  // The 2D default (a direct solve per Uzawa iteration) and FGMRES.
  for (const std::string method : {"direct", "iterative"})
    {
      const Fidus::RunSummary s =
        run("fictitious domain", "gluey", 0.1, method);
      const std::string w = "fictitious domain, gluey, " + method + ": ";
      check_range(w + "steps", s.n_steps, 5, 5);
      check_range(w + "finite state", finite_state(s), 1, 1);
      check_range(w + "minimum gap", s.min_gap, -tol, 1.);
      // The loop reaches the box rigidity 1e-3 in 2 iterations (measured
      // with both solvers), below the cap of 3: a third one would mean the
      // carried-over multiplier no longer helps.
      check_range(w + "largest Uzawa iterations", s.max_uzawa_iterations, 1, 2);
      // Per step, summed over the Uzawa iterations: 250 measured with
      // FGMRES (commit 256e7ce), far below the cap of 3 x 2000 at which the
      // solver would stop the run; none with the direct solver (whose
      // residual is checked at every solve: the run stops if it is not
      // met).
      check_range(w + "FGMRES iterations per step",
                  s.max_linear_iterations,
                  method == "direct" ? 0 : 1,
                  method == "direct" ? 0 : 400);
      // The walls move at +-0.5; no particle may outrun them by more than
      // 20 %, nor spin faster than 10 times the shear rate.
      double u_max = 0., w_max = 0.;
      for (unsigned int i = 0; i < s.velocities.size(); ++i)
        {
          u_max =
            std::max(u_max, std::hypot(s.velocities[i][0], s.velocities[i][1]));
          w_max = std::max(w_max, std::abs(s.omegas[i][2]));
        }
      check_range(w + "largest |U| after 5 steps", u_max, 0., 0.6);
      check_range(w + "largest |omega| after 5 steps", w_max, 0., 10.);
    }
  return exit_code();
}
