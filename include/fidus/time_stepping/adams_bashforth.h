#ifndef fidus_time_stepping_adams_bashforth_h
#define fidus_time_stepping_adams_bashforth_h

#include <fidus/core/shear_rate.h>
#include <fidus/time_stepping/time_scheme.h>

namespace Fidus
{
  /**
   * `Time stepping/Scheme = AB2`: the rigid velocities extrapolated to
   * the middle of the step from the last two solves (Adams-Bashforth 2),
   * and one fluid solve per step, at the positions the step reaches.
   * The extrapolation is of U divided by the shear rate, so that a jump
   * of the shear rate at a step boundary stays exact.
   */
  template <int dim>
  class AdamsBashforth2 : public TimeScheme<dim>
  {
  public:
    using typename TimeScheme<dim>::Vec3;
    using typename TimeScheme<dim>::Statistics;
    using typename TimeScheme<dim>::Stages;

    /// @p forced: the particles carry external forces, whose part of the
    /// velocity does not scale with the shear rate. @p shear must outlive
    /// the scheme.
    AdamsBashforth2(const ShearRate &shear, bool forced);

    void
    predict(const RunState      &state,
            double               dt,
            Stages              &stages,
            PredictedVelocities &predicted) override;

    Statistics
    velocities_after_step(RunState &state, Stages &stages) override;

    /// The AB2 extrapolation of @p state's velocities to the middle of a
    /// step @p dt, into @p u and @p w (also the trapezoidal predictor).
    static void
    extrapolate(const RunState    &state,
                double             dt,
                const ShearRate   &shear,
                bool               forced,
                std::vector<Vec3> &u,
                std::vector<Vec3> &w);

  private:
    const ShearRate &shear;
    const bool       forced;
  };
} // namespace Fidus

#endif
