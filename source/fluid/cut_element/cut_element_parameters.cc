// The cut finite element's entries of the subsection Fluid.

#include <cmath>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/core/parameters.h>
#include <fidus/fluid/cut_element/cut_element_parameters.h>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace Fidus
{
  using namespace dealii;


  void
  CutElementParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    prm.declare_entry(
      "Cut linear solver",
      "auto",
      Patterns::Selection("auto|automatic|direct|iterative"),
      "With 'cut finite element': 'direct' factorises the symmetric "
      "system (MUMPS, LDL^T) over all the MPI ranks; 'iterative' runs "
      "FGMRES with a block preconditioner (one geometric multigrid cycle "
      "for the velocities and rigid motions) to 'Cut linear tolerance' "
      "(on more ranks the velocity block and its multigrid are split "
      "among them, the rest runs on every rank); 'auto' (or 'automatic', "
      "its former "
      "name) is iterative in 3D above 15000 unknowns, where "
      "the factorisation is slower and takes more memory, and direct "
      "otherwise (doc/theory/cut_element.md, 'Solvers').");
    prm.declare_entry(
      "Cut minimum gap",
      "auto",
      Patterns::Anything(),
      "With 'cut finite element': the fluid solve sees every gap between "
      "two particles at least this times the smaller radius, and every "
      "gap to the box this times the radius, by shrinking the radii it "
      "gives the fluid (the contact model keeps the true radii); > 0. "
      "Smaller gaps cost more refinement; down to 1e-4 the 2D squeeze "
      "follows the lubrication law (doc/theory/cut_element.md). With "
      "'Lubrication correction' the correction adds the resistance the "
      "shrinking takes from the gaps: those below it, and the other gaps "
      "of a particle shrunk for one (doc/theory/lubrication.md). auto: "
      "1e-4, or " +
        std::to_string(corrected_minimum_gap).substr(0, 4) +
        " with 'Lubrication correction'.");
    prm.declare_entry(
      "Cut gap cells",
      "auto",
      Patterns::Anything(),
      "With 'cut finite element': the cut cells near another particle are "
      "refined until this many cells span the gap (0: only until no cell "
      "is cut by two surfaces); >= 0. auto: " +
        std::to_string(resolved_gap_cells).substr(0, 1) + ", or " +
        std::to_string(corrected_gap_cells).substr(0, 1) +
        " with 'Lubrication correction', whose bonds carry the gaps below "
        "the minimum gap: one cell across the gap at the minimum gap "
        "gives the resolved stress there, and 0 a quarter of the cost at "
        "1-2 % of the viscosity (doc/theory/lubrication.md).");
    prm.declare_entry(
      "Cut Nitsche parameter",
      "100",
      Patterns::Double(0.),
      "With 'cut finite element': the penalty of Nitsche's method that "
      "holds the fluid to each particle's rigid motion, times eta / h; > 0. "
      "Below about 100 the velocity block can lose its positive "
      "definiteness on cut slivers, which the direct solver does not "
      "notice and the iterative one cannot survive (40, the former "
      "default, stalled FGMRES on pairs at some orientations); the dense "
      "2D scene's viscosity moves by 0.06 % from 40 to 200 with every gap "
      "resolved, by 0.7 % with unrefined gaps (doc/theory/cut_element.md).");
    prm.declare_entry(
      "Cut initial guess",
      "previous solve",
      Patterns::Selection("previous solve|zero"),
      "With 'cut finite element' and its iterative solver: where FGMRES "
      "starts. 'previous solve' evaluates the last solve's velocity, "
      "pressure and rigid motions on the new mesh (the particles move a "
      "fraction of a cell per step), so fewer iterations reach the same "
      "absolute tolerance; 'zero' starts from nothing, as every solve did "
      "before (for comparisons). Either gives the answer to the solver's "
      "tolerance (doc/theory/cut_element.md).");
    prm.declare_entry(
      "Cut linear tolerance",
      "1e-8",
      Patterns::Double(),
      "With 'cut finite element' and its iterative solver: FGMRES stops "
      "when the residual of the (diagonally scaled) system is below this "
      "value times its right-hand side; in (0, 1). The particles' "
      "velocities and stresslets then lie within 1000 times this value of "
      "the exact solve's (relative to their largest; the angular "
      "velocities are the most sensitive), the suspension's stress "
      "(in eta_f gamma_dot) within this value; each decade costs about 4 "
      "FGMRES iterations. 1e-10 was the default before this was measured "
      "(doc/theory/cut_element.md, 'Solvers').");
    prm.declare_entry(
      "Cut velocity ghost penalty",
      "1e-3",
      Patterns::Double(0.),
      "With 'cut finite element': the ghost penalty on the jumps of the "
      "velocity's normal derivatives across the faces of cut cells, which "
      "bounds the unknowns of cells whose fluid part is tiny; >= 0 (0 "
      "leaves small cut pieces unstable). Larger values perturb the "
      "coarse levels: 1e-2 multiplies one disc's error by eight at "
      "a/h = 1.6 (doc/theory/cut_element.md).");
    prm.declare_entry(
      "Cut pressure ghost penalty",
      "1e-3",
      Patterns::Double(0.),
      "With 'cut finite element': the ghost penalty on the jumps of the "
      "pressure's normal derivative across the faces of cut cells; >= 0.");
    prm.leave_subsection();
  }



  void
  CutElementParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    {
      const bool corrected = prm.get_bool("Lubrication correction");
      minimum_gap          = ParameterParsing::number_or_auto(
        prm.get("Cut minimum gap"),
        "Fluid/Cut minimum gap",
        corrected ? corrected_minimum_gap : 1e-4,
        "auto or a value > 0 (the cut element cannot solve touching "
                 "particles)",
        [](const double g) { return g > 0.; });
      gap_cells = ParameterParsing::number_or_auto(
        prm.get("Cut gap cells"),
        "Fluid/Cut gap cells",
        corrected ? corrected_gap_cells : resolved_gap_cells,
        "auto or a number >= 0",
        [](const double c) { return c >= 0.; });
      nitsche          = prm.get_double("Cut Nitsche parameter");
      ghost_velocity   = prm.get_double("Cut velocity ghost penalty");
      ghost_pressure   = prm.get_double("Cut pressure ghost penalty");
      initial_guess    = prm.get("Cut initial guess");
      linear_tolerance = prm.get_double("Cut linear tolerance");
      linear_solver    = prm.get("Cut linear solver");
      // Entries away from their defaults (those of the struct, and
      // 'auto' for the two that have it): with another fluid model they
      // would do nothing (check_unused()).
      const CutElementParameters defaults;
      entries_set.clear();
      const auto note = [this](const bool set, const char *entry) {
        if (set)
          entries_set.emplace_back(entry);
      };
      note(linear_solver != "auto" && linear_solver != "automatic",
           "Cut linear solver");
      note(Utilities::trim(prm.get("Cut minimum gap")) != "auto",
           "Cut minimum gap");
      note(Utilities::trim(prm.get("Cut gap cells")) != "auto",
           "Cut gap cells");
      note(nitsche != defaults.nitsche, "Cut Nitsche parameter");
      note(ghost_velocity != defaults.ghost_velocity,
           "Cut velocity ghost penalty");
      note(ghost_pressure != defaults.ghost_pressure,
           "Cut pressure ghost penalty");
      note(initial_guess != defaults.initial_guess, "Cut initial guess");
      note(linear_tolerance != defaults.linear_tolerance,
           "Cut linear tolerance");
      // The cut element gives the correction its ranges (the minimum gap),
      // so a range set by hand would do nothing.
      ranges_set.clear();
      for (const char *entry : {"Lubrication range",
                                "Lubrication flow range",
                                "Lubrication flow edge",
                                "Lubrication tangential range"})
        if (Utilities::trim(prm.get(entry)) != "auto")
          ranges_set.emplace_back(entry);
    }
    prm.leave_subsection();
  }



  void
  CutElementParameters::check_unused(const std::string &model) const
  {
    if (!entries_set.empty())
      throw InputError("entry 'Fluid/" + entries_set.front() +
                       "' is set with 'Fluid/Model = " + model +
                       "', which does not read it; allowed: its default, or "
                       "'Fluid/Model = cut finite element'");
  }



  bool
  CutElementParameters::direct_solver(const unsigned int dimension) const
  {
    return linear_solver == "direct" ||
           (dimension == 2 && linear_solver != "iterative");
  }



  void
  CutElementParameters::check(const Parameters &scene) const
  {
    const std::string       model  = "'Fluid/Model = cut finite element'";
    const DomainParameters &domain = scene.domain;
    if (domain.boundary_condition != BoundaryCondition::linear_shear &&
        domain.boundary_condition != BoundaryCondition::sliding_walls)
      throw InputError("entry 'Domain/Boundary condition' is not 'linear "
                       "shear' or 'sliding walls' with " +
                       model +
                       "; allowed: 'linear shear' or 'sliding walls' (the "
                       "cut element's box has the shear's velocity on "
                       "every face, or on the walls y = 0, 1 with the other "
                       "faces periodic)");
    if (!(minimum_gap > 0.))
      throw InputError("entry 'Fluid/Cut minimum gap' has the value " +
                       std::to_string(minimum_gap) +
                       "; allowed: a value > 0 (the cut element cannot "
                       "solve touching particles)");
    if (!(nitsche > 0.))
      {
        std::ostringstream m;
        m << "entry 'Fluid/Cut Nitsche parameter' has the value " << nitsche
          << "; allowed: a value > 0 (without it nothing holds the fluid to "
             "the particles)";
        throw InputError(m.str());
      }
    if (!(linear_tolerance > 0. && linear_tolerance < 1.))
      {
        std::ostringstream m;
        m << "entry 'Fluid/Cut linear tolerance' has the value "
          << linear_tolerance << "; allowed: a value in (0, 1)";
        throw InputError(m.str());
      }
    // The direct solver has no start and no tolerance (it refines to
    // round-off).
    const CutElementParameters defaults;
    std::ostringstream         tolerance;
    tolerance << linear_tolerance;
    for (const auto &[entry, value, set] :
         {std::make_tuple(std::string("Cut initial guess"),
                          "'" + initial_guess + "'",
                          initial_guess != defaults.initial_guess),
          std::make_tuple(std::string("Cut linear tolerance"),
                          tolerance.str(),
                          linear_tolerance != defaults.linear_tolerance)})
      if (set && direct_solver(scene.dimension))
        throw InputError(
          "entry 'Fluid/" + entry + "' has the value " + value +
          " with the direct solver ('Fluid/Cut linear solver = " +
          linear_solver + "' in " + std::to_string(scene.dimension) +
          "D), which does not read it; allowed: its default, or "
          "'Fluid/Cut linear solver = iterative'");
    if (!scene.lubrication.enabled)
      return;
    // The cut element solves the bonds with the flow at the start's gaps.
    if (scene.lubrication.coupling ==
        LubricationParameters::Coupling::after_the_solve)
      throw InputError("entry 'Fluid/Lubrication coupling' has the value "
                       "'after the solve' with " +
                       model +
                       ", which solves the correction's bonds together with "
                       "the flow; allowed: auto, with the flow");
    if (scene.lubrication.gap_in_time != Contact::GapInTime::start)
      throw InputError("entry 'Fluid/Lubrication gap in time' is not 'start' "
                       "with " +
                       model +
                       ", which solves the correction's bonds together with "
                       "the flow at the gaps of the step's start; allowed: "
                       "start");
    if (!ranges_set.empty())
      throw InputError("entry 'Fluid/" + ranges_set.front() + "' is set with " +
                       model +
                       " and 'Fluid/Lubrication correction'; allowed: "
                       "auto (the correction starts at Fluid/Cut minimum "
                       "gap, the gap the cut element resolves)");
    // Below the roughness the correction's resistance stops growing, so a
    // minimum gap at or below it leaves nothing to correct.
    if (!(minimum_gap > scene.contact.roughness))
      {
        std::ostringstream m;
        m << "entry 'Fluid/Cut minimum gap' has the value " << minimum_gap
          << " with 'Fluid/Lubrication correction' and 'Contact/Roughness = "
          << scene.contact.roughness
          << "'; allowed: a gap above the roughness (the correction adds "
             "the resistance between the two, so it would add nothing)";
        throw InputError(m.str());
      }
  }
} // namespace Fidus
