// The sub-grid lubrication's entries of the subsection Fluid.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/lubrication/lubrication_parameters.h>
#include <sstream>
#include <utility>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  void
  LubricationParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    prm.declare_entry(
      "Lubrication correction",
      "false",
      Patterns::Bool(),
      "Add the squeeze resistance of the gaps the mesh cannot resolve "
      "(particle pairs and particle-wall gaps below 'Lubrication range'), "
      "implicitly in the particle velocities, minus the part the mesh "
      "carries (doc/lubrication.md). Meant with 'Shared cells = fluid', "
      "where close pairs are no longer held as one rigid doublet. false "
      "keeps the seed's model.");
    prm.declare_entry(
      "Lubrication coupling",
      "auto",
      Patterns::Selection("auto|after the solve|with the flow"),
      "With 'Lubrication correction', how the sub-grid resistance meets "
      "the fluid solve. after the solve: the solve's rigid velocities are "
      "corrected afterwards, with each particle's isolated drag standing "
      "for the fluid around it (one solve per step). with the flow: the "
      "bonds' forces and torques act on the particles inside the fluid "
      "solve, iterated with it until the rigid velocities agree to "
      "'Lubrication coupling tolerance' (a few solves per step), so that "
      "the flow around a close pair is that of the pair's lubricated "
      "motion. auto: with the flow for the cut finite element (its only "
      "way); for the fictitious domain, with the flow where the particles "
      "fill less than 15 % of the box (a pair, a dilute suspension: the "
      "closing rates) and 'Lubrication gap in time = start', after the "
      "solve otherwise (a dense suspension: a fifth of the cost in 3D). "
      "Measured in doc/theory/lubrication.md, 'Which coupling'.");
    prm.declare_entry(
      "Lubrication coupling tolerance",
      "1e-3",
      Patterns::Double(0.),
      "With 'Lubrication coupling = with the flow' on the fictitious "
      "domain: the iteration of the bonds with the fluid solve stops when "
      "no particle's rigid velocity (or angular velocity times its "
      "radius) changes by more than this fraction of the largest rigid "
      "speed, > 0.");
    prm.declare_entry(
      "Lubrication tangential terms",
      "true",
      Patterns::Bool(),
      "With 'Lubrication correction': also correct the tangential terms "
      "of each close gap, the resistance to the two surfaces sliding past "
      "each other and to their relative rotation (singular like h^-1/2 "
      "for discs, log(1/h) for spheres), with the angular velocities "
      "among the unknowns (doc/lubrication.md). false: the normal squeeze "
      "only.");
    prm.declare_entry(
      "Lubrication gap in time",
      "start",
      Patterns::Selection("start|closing mean|step mean"),
      "With 'Lubrication correction', the gaps whose squeeze resistance "
      "slows a pair over a time step. start: the gap at the start of the "
      "step (explicit). step mean: the mean of the resistance over the "
      "gaps the step passes through, from the start to where the "
      "corrected velocities take the pair (found by a few re-solves of "
      "the correction's small system), so that a pair driven steadily "
      "lands where the exact squeeze does. closing mean: the same for a "
      "closing gap, the start's for an opening one. Measured on a dense "
      "3D suspension in doc/cookbooks/rheology_bulk_3d.md, 'The time "
      "step'.");
    prm.declare_entry(
      "Lubrication range",
      "auto",
      Patterns::Anything(),
      "Gap, in finest cell sizes, below which the lubrication correction "
      "acts and above which the mesh is taken to resolve the squeeze "
      "flow, > 0. auto: between particles 0.65 in 2D and 0.3 in 3D; "
      "between a particle and a wall 0.33 in 2D and 0.2 in 3D: the "
      "fraction of a cell down to which the mesh carries the squeeze of "
      "a pushed particle (measured against exact solutions and resolved "
      "meshes in doc/lubrication.md). A number sets both; two numbers, "
      "separated by a comma, set the particle pairs' and the walls'.");
    prm.declare_entry(
      "Lubrication tangential range",
      "auto",
      Patterns::Anything(),
      "Gap, in finest cell sizes, down to which the mesh carries the "
      "tangential resistance of two surfaces sliding past each other, "
      "> 0: below it the correction adds the tangential terms of the gap. "
      "Against a wall the mesh resolves sliding less far down than the "
      "squeeze, so this may exceed 'Lubrication range'. auto: between "
      "particles the pairs' 'Lubrication range'; between a particle and "
      "a wall 1 in 2D and the walls' 'Lubrication range' in 3D. The 2D "
      "values were measured on discs pushed past each other and along a "
      "wall against a resolved mesh (doc/lubrication.md). A number sets "
      "both; two numbers, separated by a comma, set the particle pairs' "
      "and the walls'.");
    prm.declare_entry(
      "Lubrication flow range",
      "auto",
      Patterns::Anything(),
      "Gap, in finest cell sizes, whose squeeze resistance the fluid solve "
      "shows when the ambient flow, not a force, closes the gap between "
      "two particles, > 0. The mesh resists a flow-driven approach less "
      "than a force-driven one, so the correction treats the part of the "
      "fluid's velocities that 'Particles/External force' drives with "
      "'Lubrication range' and the rest with this one; in 3D the gap the "
      "mesh shows rises from this one at contact to 'Lubrication flow "
      "edge'. auto: in 3D 0.54 at 'Solid retraction = 0' and 0.62 at 0.3, "
      "linear in the retraction, fitted with the edge on two spheres held "
      "in shear against Batchelor & Green; 2 in 2D, chosen on a "
      "lubricated pair in shear, which it keeps from overlapping at every "
      "level (two discs held in shear would want 0.7-1; "
      "doc/lubrication.md says why it stays).");
    prm.declare_entry(
      "Lubrication flow edge",
      "auto",
      Patterns::Anything(),
      "Gap, in finest cell sizes, at which the mesh's response to a "
      "flow-driven approach starts to miss the squeeze, >= 'Lubrication "
      "flow range'. Below it the correction takes the fluid solve to show "
      "the squeeze of a gap that rises linearly from the flow range at "
      "contact to this gap; equal to the flow range, it shows the flow "
      "range's squeeze at every gap below it (a step). auto: with an auto "
      "flow range in 3D, 0.74 at 'Solid retraction = 0' and 0.87 at 0.3, "
      "linear in the retraction, fitted with it on two spheres held in "
      "shear against Batchelor & Green at gaps from 0.02a to 0.5a and "
      "generic positions in the mesh; otherwise the flow range "
      "(doc/theory/lubrication.md).");
    prm.leave_subsection();
  }



  namespace
  {
    /// The 3D flow range and edge, in finest cells, for the solid
    /// retraction @p c: fitted together on two spheres held in shear at
    /// generic positions in the mesh at c = 0 and c = 0.3, linear in c
    /// (doc/theory/lubrication.md, "Two ranges"). A retracted solid leaves
    /// more of each surface's cells to the fluid, so the mesh loses the
    /// squeeze further out.
    std::pair<double, double>
    auto_flow_gaps_3d(const double c)
    {
      const double s = c / 0.3;
      return {0.54 + (0.62 - 0.54) * s, 0.74 + (0.87 - 0.74) * s};
    }
  } // namespace



  void
  LubricationParameters::parse(ParameterHandler  &prm,
                               const unsigned int dim,
                               const double       solid_retraction)
  {
    const auto [auto_flow_range_3d, auto_flow_edge_3d] =
      auto_flow_gaps_3d(solid_retraction);
    prm.enter_subsection("Fluid");
    enabled = prm.get_bool("Lubrication correction");
    // An entry that is 'auto' (then {auto_pairs, auto_walls}), one gap
    // in cells for both, or two: the particle pairs' and the walls'.
    const auto pair_and_wall_ranges = [&](const std::string &entry,
                                          const double       auto_pairs,
                                          const double       auto_walls) {
      const std::string text = Utilities::trim(prm.get(entry));
      if (text == "auto")
        return std::vector<double>{auto_pairs, auto_walls};
      const std::vector<double> v =
        ParameterParsing::parse_numbers(text, "Fluid/" + entry);
      if (v.empty() || v.size() > 2)
        throw InputError("entry 'Fluid/" + entry + "' has the value '" + text +
                         "'; allowed: auto, one gap in finest cell sizes "
                         "> 0 (particle pairs and walls), or two "
                         "(particle pairs, walls)");
      return std::vector<double>{v[0], v.back()};
    };
    // The 3D values and the 2D walls' and pairs' squeeze ranges are the
    // fraction of a cell down to which the mesh carries a pushed
    // particle's squeeze (doc/theory/lubrication.md).
    const std::vector<double> squeeze =
      pair_and_wall_ranges("Lubrication range",
                           dim == 3 ? 0.3 : 0.65,
                           dim == 3 ? 0.2 : 0.33);
    range      = squeeze[0];
    wall_range = squeeze[1];
    const std::vector<double> tangential_ranges =
      pair_and_wall_ranges("Lubrication tangential range",
                           range,
                           dim == 3 ? wall_range : 1.);
    tangential_range      = tangential_ranges[0];
    wall_tangential_range = tangential_ranges[1];
    // 2 in 2D: the range with which a lubricated pair in shear does not
    // overlap at any level. A held pair would want 0.7-1, but that
    // changes the dense scene's viscosity by a third, with no reference
    // for it yet (doc/theory/lubrication.md).
    flow_range = ParameterParsing::number_or_auto(
      prm.get("Lubrication flow range"),
      "Fluid/Lubrication flow range",
      dim == 3 ? auto_flow_range_3d : 2.,
      "auto or one gap in finest cell sizes > 0");
    // The ramp's edge in 3D is fitted on held sheared pairs; 2D keeps the
    // step (doc/theory/lubrication.md).
    const bool flow_range_auto =
      Utilities::trim(prm.get("Lubrication flow range")) == "auto";
    flow_edge = ParameterParsing::number_or_auto(
      prm.get("Lubrication flow edge"),
      "Fluid/Lubrication flow edge",
      dim == 3 && flow_range_auto ? auto_flow_edge_3d : flow_range,
      "auto or one gap in finest cell sizes > 0");
    const std::string coupling_text = prm.get("Lubrication coupling");
    coupling = coupling_text == "after the solve" ? Coupling::after_the_solve :
               coupling_text == "with the flow"   ? Coupling::with_the_flow :
                                                    Coupling::automatic;
    coupling_tolerance    = prm.get_double("Lubrication coupling tolerance");
    tangential            = prm.get_bool("Lubrication tangential terms");
    const std::string gap = prm.get("Lubrication gap in time");
    gap_in_time           = gap == "step mean" ? Contact::GapInTime::step_mean :
                            gap == "closing mean" ? Contact::GapInTime::closing_mean :
                                                    Contact::GapInTime::start;
    prm.leave_subsection();
  }



  void
  LubricationParameters::check() const
  {
    const auto require_gap = [&](const std::string &entry, const double gap) {
      if (enabled && !(gap > 0.))
        {
          std::ostringstream m;
          m << "entry 'Fluid/" << entry << "' has the value " << gap
            << "; allowed: a gap in finest cell sizes > 0 when 'Fluid/"
            << "Lubrication correction' is true";
          throw InputError(m.str());
        }
    };
    if (!enabled && gap_in_time != Contact::GapInTime::start)
      throw InputError("entry 'Fluid/Lubrication gap in time' is set "
                       "without 'Fluid/Lubrication correction = true', which "
                       "it belongs to; allowed: start, or the correction on");
    if (!enabled && coupling != Coupling::automatic)
      throw InputError("entry 'Fluid/Lubrication coupling' is set without "
                       "'Fluid/Lubrication correction = true', which it "
                       "belongs to; allowed: auto, or the correction on");
    if (enabled && !(coupling_tolerance > 0.))
      {
        std::ostringstream m;
        m << "entry 'Fluid/Lubrication coupling tolerance' has the value "
          << coupling_tolerance << "; allowed: a number > 0";
        throw InputError(m.str());
      }
    require_gap("Lubrication range", range);
    require_gap("Lubrication range", wall_range);
    require_gap("Lubrication flow range", flow_range);
    require_gap("Lubrication tangential range", tangential_range);
    require_gap("Lubrication tangential range", wall_tangential_range);
    if (enabled && flow_edge < flow_range)
      {
        std::ostringstream m;
        m << "entry 'Fluid/Lubrication flow edge' has the value " << flow_edge
          << ", below 'Fluid/Lubrication flow range' = " << flow_range
          << "; allowed: a gap in finest cell sizes >= the flow range";
        throw InputError(m.str());
      }
  }



  Contact::LubricationSettings
  LubricationParameters::settings(const unsigned int dim,
                                  const double       h,
                                  const double       viscosity,
                                  const double       roughness,
                                  const double       drag,
                                  const bool         resolves_gap_flow) const
  {
    Contact::LubricationSettings ls;
    ls.dimension             = dim;
    ls.viscosity             = viscosity;
    ls.range                 = range * h;
    ls.wall_range            = wall_range * h;
    ls.flow_range            = flow_range * h;
    ls.flow_edge             = flow_edge * h;
    ls.tangential_range      = tangential_range * h;
    ls.tangential_wall_range = wall_tangential_range * h;
    ls.roughness             = roughness;
    ls.nothing_resolved      = !resolves_gap_flow;
    ls.drag                  = drag;
    ls.tangential            = tangential;
    ls.gap_in_time           = gap_in_time;
    return ls;
  }
} // namespace Fidus
