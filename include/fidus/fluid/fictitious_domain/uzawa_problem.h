#ifndef fidus_fluid_uzawa_problem_h
#define fidus_fluid_uzawa_problem_h

#include <fidus/fluid/fictitious_domain/rigid_motion.h>
#include <vector>

namespace Fidus
{
  /**
   * What the Uzawa loop iterates on: a penalised Stokes system with a
   * rigidity multiplier lambda, seen only through the operations the loop
   * needs. StokesSolver implements it on its finite-element system; the
   * test tests/fluid/uzawa_loop implements it with a model whose residuals
   * are known, so that the stopping rules are checked apart from the
   * discretisation.
   */
  class UzawaProblem
  {
  public:
    /// The strain left in the solid after a solve.
    struct Residual
    {
      /// sqrt(int |e(u)|^2 / int_box |e(u)|^2) over the solid outside
      /// shared cells (what the Uzawa loop drives down by default).
      double held = 0.;
      /// The same over the solid in shared cells (released, reported only).
      double released = 0.;
      /// The box's rms shear rate sqrt(2 int_box |e(u)|^2 / |box|).
      double shear_rate = 0.;
      /// The largest over the particles of the rms strain rate in the
      /// particle's held solid relative to the box's shear rate,
      /// max_i sqrt(int_{P_i} |e(u)|^2 / |P_i|) / shear_rate: a measure
      /// that does not depend on the box's size or the particle count.
      double particle = 0.;
    };

    virtual ~UzawaProblem() = default;

    /// Build the right-hand side that the current multiplier loads.
    virtual void
    load_multiplier() = 0;

    /// Solve for the velocity with the current right-hand side, from
    /// zero, to @p tolerance relative to the right-hand side. Returns the
    /// number of Krylov iterations.
    virtual unsigned int
    solve_velocity(double tolerance) = 0;

    /// The strain the last velocity leaves in the solid.
    virtual Residual
    rigidity_residual() const = 0;

    /// The particles' rigid velocities from the last velocity.
    virtual std::vector<RigidMotion>
    rigid_motions() const = 0;

    /// The radius of particle @p i (the length scale of its rotation).
    virtual double
    particle_radius(unsigned int i) const = 0;

    /// The plain Uzawa update lambda += rho M u (M: the held solid).
    virtual void
    update_multiplier() = 0;
  };
} // namespace Fidus

#endif
