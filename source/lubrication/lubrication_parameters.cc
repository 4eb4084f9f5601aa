// The sub-grid lubrication's entries of the subsection Fluid.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/lubrication/lubrication_parameters.h>
#include <sstream>
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
      "'Lubrication range' and the rest with this one. auto: 0.45 in 3D, "
      "measured on two spheres held in shear against Batchelor & Green, "
      "and 2 in 2D, chosen on a lubricated pair in shear, which it keeps "
      "from overlapping at every level (two discs held in shear would "
      "want 0.7-1; doc/lubrication.md says why it stays).");
    prm.leave_subsection();
  }



  void
  LubricationParameters::parse(ParameterHandler &prm, const unsigned int dim)
  {
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
      dim == 3 ? 0.45 : 2.,
      "auto or one gap in finest cell sizes > 0");
    tangential = prm.get_bool("Lubrication tangential terms");
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
    require_gap("Lubrication range", range);
    require_gap("Lubrication range", wall_range);
    require_gap("Lubrication flow range", flow_range);
    require_gap("Lubrication tangential range", tangential_range);
    require_gap("Lubrication tangential range", wall_tangential_range);
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
    ls.tangential_range      = tangential_range * h;
    ls.tangential_wall_range = wall_tangential_range * h;
    ls.roughness             = roughness;
    ls.nothing_resolved      = !resolves_gap_flow;
    ls.drag                  = drag;
    ls.tangential            = tangential;
    return ls;
  }
} // namespace Fidus
