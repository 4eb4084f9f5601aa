#ifndef fidus_time_stepping_trapezoidal_scheme_h
#define fidus_time_stepping_trapezoidal_scheme_h

#include <fidus/core/shear_rate.h>
#include <fidus/simulation/box_geometry.h>
#include <fidus/time_stepping/time_scheme.h>

namespace Fidus
{
  /**
   * `Time stepping/Scheme = trapezoidal`: X+ = X + dt (U(X) + U(X+)) / 2,
   * symmetric in time, so that a reversed shear brings the particles back
   * (AB2's O(dt^2) error does not cancel under reversal). X+ is found by
   * `Trapezoidal iterations` fixed-point passes from the AB2 prediction;
   * each pass corrects and projects the current velocities as a trial,
   * solves the fluid where they lead and averages. The last pass's solve
   * stands for the one after the move, so one pass costs what AB2 costs.
   */
  template <int dim>
  class TrapezoidalScheme : public TimeScheme<dim>
  {
  public:
    using typename TimeScheme<dim>::Vec3;
    using typename TimeScheme<dim>::Statistics;
    using typename TimeScheme<dim>::Stages;

    /// @p forced as for AdamsBashforth2; @p boundary_follows_shear: the
    /// boundary velocity is proportional to the shear rate (not the exact
    /// inclusion's). @p shear and @p box must outlive the scheme.
    TrapezoidalScheme(const ShearRate        &shear,
                      const BoxGeometry<dim> &box,
                      bool                    forced,
                      bool                    boundary_follows_shear,
                      unsigned int            passes);

    void
    predict(const RunState      &state,
            double               dt,
            Stages              &stages,
            PredictedVelocities &predicted) override;

    Statistics
    velocities_after_step(RunState &state, Stages &stages) override;

  private:
    const ShearRate        &shear;
    const BoxGeometry<dim> &box;
    const bool              forced, boundary_follows_shear;
    const unsigned int      passes;
    /// The last pass's velocities at the end of the step and the
    /// statistics of all passes; valid after predict().
    std::vector<Vec3> U_end, W_end;
    Statistics        pass_statistics;
    bool              have_end = false;
  };
} // namespace Fidus

#endif
