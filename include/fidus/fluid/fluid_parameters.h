#ifndef fidus_fluid_fluid_parameters_h
#define fidus_fluid_fluid_parameters_h

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /// How particle velocities are obtained (Fluid/Model).
  enum class FluidModelType
  {
    fictitious_domain,
    undisturbed_shear,
    /// The fluid outside the particles only, rigid motions by Nitsche's
    /// method (CutStokesInclusion).
    cut_finite_element
  };

  /**
   * What every fluid model shares: the model itself, the viscosity and the
   * velocity degree (entries of the subsection Fluid). Each model's own
   * entries are declared by the model's parameters (FictitiousDomain-
   * Parameters, CutElementParameters), the sub-grid correction's by
   * LubricationParameters, in the same subsection.
   */
  struct FluidParameters
  {
    /// Register Fluid/Model, Viscosity and Velocity degree.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back.
    void
    parse(dealii::ParameterHandler &prm);

    /// Throw an InputError if the viscosity is not positive.
    void
    check() const;

    FluidModelType model           = FluidModelType::fictitious_domain;
    double         viscosity       = 1.;
    unsigned int   velocity_degree = 2;
  };
} // namespace Fidus

#endif
