#ifndef fidus_lubrication_lubrication_parameters_h
#define fidus_lubrication_lubrication_parameters_h

#include <fidus/lubrication/lubrication_correction.h>

namespace dealii
{
  class ParameterHandler;
}

namespace Fidus
{
  /**
   * The sub-grid lubrication correction's entries (subsection Fluid, names
   * beginning with 'Lubrication'), with their 'auto' values resolved for
   * the dimension. Ranges are gaps in finest cell sizes. The header is free
   * of deal.II, like the lubrication library; declare() and parse() live in
   * the deal.II part of fidus (fidus_core).
   */
  struct LubricationParameters
  {
    /// Register the lubrication entries of the subsection Fluid.
    static void
    declare(dealii::ParameterHandler &prm);

    /// Read them back, 'auto' resolved for @p dim dimensions and the
    /// fictitious domain's @p solid_retraction (Fluid/Solid retraction, in
    /// finest cells: the 3D flow range and edge depend on it).
    void
    parse(dealii::ParameterHandler &prm,
          const unsigned int        dim,
          double                    solid_retraction);

    /// With the correction on, throw an InputError for a range that is not
    /// positive.
    void
    check() const;

    /// The lubrication library's settings for a scene in @p dim dimensions
    /// with the finest cell size @p h (the ranges are in cells), the fluid
    /// viscosity @p viscosity, the contact's @p roughness and drag
    /// coefficient @p drag, and a fluid model that resolves part of a
    /// thin gap's flow or not (@p resolves_gap_flow).
    Contact::LubricationSettings
    settings(const unsigned int dim,
             const double       h,
             const double       viscosity,
             const double       roughness,
             const double       drag,
             const bool         resolves_gap_flow) const;

    /// Fluid/Lubrication correction.
    bool enabled = false;
    /// How the correction meets the fluid solve (Fluid/Lubrication
    /// coupling).
    enum class Coupling
    {
      /// the fluid model's own way: with the flow for the cut finite
      /// element; for the fictitious domain, with the flow in a dilute
      /// scene and after the solve in a dense one (resolved by
      /// Parameters::resolve_lubrication_coupling())
      automatic,
      /// the rigid velocities of the solve corrected afterwards, with the
      /// particles' isolated drags standing for the fluid
      after_the_solve,
      /// the bonds' loads acting in the fluid solve, solved together
      with_the_flow
    };
    Coupling coupling = Coupling::automatic;
    /// Below this volume fraction of the particles, 'auto' solves the
    /// fictitious domain's bonds with the flow (doc/theory/lubrication.md,
    /// "Which coupling").
    static constexpr double dilute_fraction = 0.15;
    /// Fluid/Lubrication coupling tolerance: the coupled iteration stops
    /// when no rigid velocity changes by more than this fraction of the
    /// largest one.
    double coupling_tolerance = 1e-3;
    /// Ranges of particle pairs and of particle-wall gaps below which the
    /// squeeze is corrected (Fluid/Lubrication range).
    double range      = 2.;
    double wall_range = 2.;
    /// The pairs' range in the fluid solve's response to the flow
    /// (Fluid/Lubrication flow range).
    double flow_range = 2.;
    /// The gap where the flow's resolved gap meets the true one
    /// (Fluid/Lubrication flow edge); equal to flow_range: a step.
    double flow_edge = 2.;
    /// Fluid/Lubrication tangential range of particle pairs and of
    /// particle-wall gaps.
    double tangential_range      = 2.;
    double wall_tangential_range = 1.;
    /// Also the tangential terms (Fluid/Lubrication tangential terms).
    bool tangential = true;
    /// Fluid/Lubrication gap in time.
    Contact::GapInTime gap_in_time = Contact::GapInTime::start;
  };
} // namespace Fidus

#endif
