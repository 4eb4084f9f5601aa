// Two discs closer than a cell ('Fluid/Shared cells'). The pair lies on
// the extensional diagonal through the centre of the box in linear shear,
// gap 2e-3 a cell (1/64) being 1.6e-2: point-symmetric, so U_1 = -U_0 and
// omega_1 = omega_0 in both models.
//  - 'rigid' (the seed's model): the cells between them must move
//    rigidly with both, so the pair moves as one rigid doublet: no relative
//    velocity along the line of centres, each disc and the doublet turning
//    at -g/2.
//  - 'fluid': the solid of those cells is released (reported apart: count
//    and residual), the Uzawa loop converges on the rest, and with no
//    lubrication below the mesh scale the pair separates along the
//    extensional axis at a sizeable fraction of the undisturbed rate
//    g r / 2, which bounds it from above.
// Exact 2D pair hydrodynamics give a separation rate of order
// (gap/a)^(3/2) g r / 2, about 1e-2 of the undisturbed one here.
// Then the default, 'auto': released with a contact model or the
// lubrication correction, rigid with neither; 'Reuse multiplier = auto'
// warm-starts only with rigid shared cells.

#include "../fidus_test.h"

#include <fidus/core/parameters.h>
#include <fidus/simulation/simulation.h>

using namespace FidusTest;

namespace
{
  const double a = 0.05, gap = 2e-3;
  // Half the centre distance along each axis.
  const double h = 0.5 * (2. * a + gap) / std::sqrt(2.);

  Fidus::RunSummary
  run(const std::string &shared_cells)
  {
    std::ostringstream prm;
    prm
      << std::setprecision(17) << "set Dimension = 2\n"
      << "set Output directory = output_" << shared_cells
      << "\n"
      // Solid retraction 0: the seed's model, in which the bounds below were
      // measured.
      << "subsection Fluid\n  set Solid retraction = 0\n  set Rigidity tolerance = 1e-3\n"
         "  set Rigidity measure = box\n"
      << "  set Maximum Uzawa iterations = 30\n"
      << "  set Shared cells = " << shared_cells << "\nend\n"
      << "subsection Particles\n  set Radius = " << a
      << "\n  set Positions = " << 0.5 - h << ", " << 0.5 - h << "; " << 0.5 + h
      << ", " << 0.5 + h << "\nend\n"
      << "subsection Time stepping\n  set End time = 0\nend\n"
      << "subsection Mesh refinement\n  set Maximum level = 6\nend\n"
      << "subsection Output\n  set Verbosity = quiet\nend\n";
    return Fidus::run_simulation(Fidus::read_parameters_from_string(prm.str()));
  }

  void
  check(const std::string &name, const Fidus::RunSummary &s)
  {
    const double g  = 1.;
    const auto  &U0 = s.velocities[0], &U1 = s.velocities[1];
    const auto  &W0 = s.omegas[0], &W1 = s.omegas[1];
    check_range(name + ": Uzawa loop converged (failures)",
                s.uzawa_failures,
                0,
                0);
    check_range(name + ": |U_0 + U_1| / (g a)",
                std::hypot(U0[0] + U1[0], U0[1] + U1[1]) / (g * a),
                0.,
                1e-3);
    check_range(name + ": |omega_0 - omega_1| / (g/2)",
                std::abs(W0[2] - W1[2]) / (0.5 * g),
                0.,
                1e-3);
    check_range(name + ": omega_0 / (-g/2)", W0[2] / (-0.5 * g), 0.99, 1.01);
  }

  /// The parsed (release shared cells, reuse multiplier) of a scene with
  /// the given contact model, lubrication and Fluid entries ("" = default).
  std::pair<bool, bool>
  resolved(const std::string &contact,
           const bool         lubrication,
           const std::string &shared_cells,
           const std::string &reuse)
  {
    std::ostringstream prm;
    prm << "set Dimension = 2\nsubsection Fluid\n"
        << "  set Lubrication correction = " << (lubrication ? "true" : "false")
        << "\n"
        << (shared_cells.empty() ?
              "" :
              "  set Shared cells = " + shared_cells + "\n")
        << (reuse.empty() ? "" : "  set Reuse multiplier = " + reuse + "\n")
        << "end\nsubsection Particles\n  set Radius = 0.05\n"
        << "  set Positions = 0.3, 0.5; 0.7, 0.5\nend\n"
        << (contact.empty() ?
              "" :
              "subsection Contact\n  set Model = " + contact + "\nend\n");
    const Fidus::Parameters p = Fidus::read_parameters_from_string(prm.str());
    return {p.fictitious_domain.release_shared_cells,
            p.fictitious_domain.reuse_multiplier};
  }

  /// Separation rate along the line of centres over the undisturbed one.
  double
  separation(const Fidus::RunSummary &s)
  {
    const auto  &U0 = s.velocities[0], &U1 = s.velocities[1];
    const double r = 2. * std::sqrt(2.) * h;
    return ((U1[0] - U0[0]) + (U1[1] - U0[1])) / std::sqrt(2.) / (0.5 * r);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  redirect_warnings();

  const Fidus::RunSummary rigid = run("rigid");
  check("rigid", rigid);
  check_range("rigid: no cells released", rigid.max_shared_cells, 0, 0);
  check_range("rigid: separation rate / (g r / 2) (rigid doublet)",
              separation(rigid),
              -1e-2,
              1e-2);

  const Fidus::RunSummary fluid = run("fluid");
  check("fluid", fluid);
  check_range("fluid: rigidity residual outside shared cells",
              fluid.max_rigidity_residual,
              0.,
              1e-3);
  check_range("fluid: shared cells released", fluid.max_shared_cells, 1, 1000);
  check_range("fluid: released residual reported (> tolerance)",
              fluid.max_shared_residual,
              1e-3,
              1.);
  check_range("fluid: separation rate / (g r / 2) (no lubrication)",
              separation(fluid),
              0.1,
              1.);

  // The defaults (auto). The default contact model is gluey.
  const auto by_default = resolved("", false, "", "");
  check_range("auto, gluey: released", by_default.first, 1, 1);
  check_range("auto, gluey: no warm start", by_default.second, 0, 0);
  const auto inelastic = resolved("inelastic", false, "", "");
  check_range("auto, inelastic: released", inelastic.first, 1, 1);
  const auto none = resolved("none", false, "", "");
  check_range("auto, none: rigid", none.first, 0, 0);
  check_range("auto, none: warm start", none.second, 1, 1);
  const auto lubricated = resolved("none", true, "", "");
  check_range("auto, none with lubrication: released", lubricated.first, 1, 1);
  const auto pinned = resolved("gluey", false, "rigid", "");
  check_range("rigid, gluey: rigid", pinned.first, 0, 0);
  check_range("rigid, gluey: warm start", pinned.second, 1, 1);
  const auto forced = resolved("none", false, "fluid", "true");
  check_range("fluid, reuse true: released", forced.first, 1, 1);
  check_range("fluid, reuse true: warm start", forced.second, 1, 1);
  return exit_code();
}
