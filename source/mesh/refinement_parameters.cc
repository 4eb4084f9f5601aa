// The entries of the subsection Mesh refinement.

#include <deal.II/base/parameter_handler.h>
#include <fidus/core/input_error.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/mesh/refinement_parameters.h>

namespace Fidus
{
  using namespace dealii;

  void
  RefinementParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh refinement");
    prm.declare_entry("Initial global refinement",
                      "3",
                      Patterns::Integer(0, 12),
                      "Uniform refinements of the coarse box mesh (whose "
                      "cells are near-cubes of the smallest box side).");
    prm.declare_entry("Minimum level",
                      "3",
                      Patterns::Integer(0, 15),
                      "Coarsest level far from particles, <= Initial "
                      "global refinement.");
    prm.declare_entry("Maximum level",
                      "8",
                      Patterns::Integer(0, 15),
                      "Finest level at particle surfaces and in gaps, >= "
                      "Initial global refinement.");
    prm.declare_entry(
      "Interface band",
      "1",
      Patterns::Double(0.),
      "Cells closer to a particle surface than this many cell sizes (of "
      "their own size) are refined, > 0. 1 gives the error of 2 or 3 "
      "with 40 % fewer cells (doc/performance.md).");
    prm.declare_entry("Gap refinement distance",
                      "0.5",
                      Patterns::Double(0.),
                      "Cells closer than this distance (relative to the "
                      "smaller radius) to both surfaces of a pair whose gap "
                      "is below it are refined to the maximum level.");
    prm.declare_entry("Remesh fraction",
                      "0.5",
                      Patterns::Double(0.),
                      "Remesh only once a particle has moved more than this "
                      "fraction of the band (band * finest cell size) since "
                      "the last remesh; 0 remeshes every step.");
    prm.leave_subsection();
  }



  void
  RefinementParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh refinement");
    {
      initial_global_refinement = prm.get_integer("Initial global refinement");
      minimum_level             = prm.get_integer("Minimum level");
      maximum_level             = prm.get_integer("Maximum level");
      interface_band            = prm.get_double("Interface band");
      gap_refinement_distance   = prm.get_double("Gap refinement distance");
      remesh_fraction           = prm.get_double("Remesh fraction");
    }
    prm.leave_subsection();
  }



  void
  RefinementParameters::check() const
  {
    ParameterParsing::require_positive(interface_band,
                                       "Mesh refinement/Interface band");
    if (minimum_level > initial_global_refinement ||
        initial_global_refinement > maximum_level)
      throw InputError(
        "entries 'Mesh refinement/Minimum level' = " +
        std::to_string(minimum_level) + ", 'Initial global refinement' = " +
        std::to_string(initial_global_refinement) +
        ", 'Maximum level' = " + std::to_string(maximum_level) +
        "; allowed: Minimum level <= Initial global refinement <= Maximum "
        "level");
  }
} // namespace Fidus
