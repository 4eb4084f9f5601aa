// The entries of the subsection Fluid that every fluid model shares.

#include <deal.II/base/parameter_handler.h>
#include <fidus/core/parameter_parsing.h>
#include <fidus/fluid/fluid_parameters.h>

namespace Fidus
{
  using namespace dealii;

  void
  FluidParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    prm.declare_entry(
      "Model",
      "fictitious domain",
      Patterns::Selection(
        "fictitious domain|undisturbed shear|cut finite element"),
      "'fictitious domain': Stokes with penalised viscosity and a rigidity "
      "multiplier on an adaptive mesh. 'undisturbed shear': particles move "
      "with the undisturbed shear flow at their centre (no mesh, no "
      "hydrodynamic interaction). 'cut finite element': Stokes in the "
      "fluid outside the particles only, their rigid motions imposed by "
      "Nitsche's method, on a mesh built for every solve (from Mesh "
      "refinement/Minimum level to Maximum level at the surfaces, thin "
      "gaps, between particles and to the walls, further); one solve "
      "(Cut linear solver) on any number of MPI ranks (on one machine "
      "fastest on one rank, with the machine's cores as threads, at most "
      "DEAL_II_NUM_THREADS), in any box, in linear shear or between "
      "sliding walls, from a pair to a dense suspension "
      "(doc/theory/cut_element.md).");
    prm.declare_entry("Viscosity",
                      "1",
                      Patterns::Double(0.),
                      "Fluid viscosity eta_f [pressure * time], > 0.");
    prm.declare_entry("Velocity degree",
                      "2",
                      Patterns::Integer(2, 4),
                      "Polynomial degree of the velocity (Taylor-Hood "
                      "Q(k)/Q(k-1)), 2 to 4.");
    prm.leave_subsection();
  }



  void
  FluidParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    {
      const std::string name = prm.get("Model");
      model = name == "fictitious domain" ? FluidModelType::fictitious_domain :
              name == "undisturbed shear" ? FluidModelType::undisturbed_shear :
                                            FluidModelType::cut_finite_element;
      viscosity       = prm.get_double("Viscosity");
      velocity_degree = prm.get_integer("Velocity degree");
    }
    prm.leave_subsection();
  }



  void
  FluidParameters::check() const
  {
    ParameterParsing::require_positive(viscosity, "Fluid/Viscosity");
  }
} // namespace Fidus
