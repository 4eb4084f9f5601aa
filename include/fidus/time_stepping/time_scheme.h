#ifndef fidus_time_stepping_time_scheme_h
#define fidus_time_stepping_time_scheme_h

#include <array>
#include <fidus/fluid/fluid_model.h>
#include <vector>

namespace Fidus
{
  struct RunState;

  /**
   * The velocities a time step predicts for the particles, before the
   * lubrication correction and the contact projection act on them.
   */
  struct PredictedVelocities
  {
    using Vec3 = std::array<double, 3>;
    /// Translational and angular velocities over the step.
    std::vector<Vec3> u, w;
    /// Where the particles are estimated to be at the middle of the step,
    /// for the normals of glued pairs (ContactProjector::project); empty:
    /// the projection takes the start of the step.
    std::vector<Vec3> middle;
  };



  /**
   * How a time step gets the particles' velocities: an interface with two
   * schemes, Adams-Bashforth 2 (AdamsBashforth2) and the trapezoidal
   * predictor-corrector (TrapezoidalScheme), picked by `Time
   * stepping/Scheme`. The time loop asks the scheme for the velocities of
   * the step (predict()), corrects and projects them, moves the
   * particles, and asks it for the velocities at the new positions
   * (velocities_after_step()). A scheme that needs the fluid or the
   * contact correction at other positions asks the Stages it is given.
   */
  template <int dim>
  class TimeScheme
  {
  public:
    using Vec3       = std::array<double, 3>;
    using Statistics = typename FluidModel<dim>::Statistics;
    using SolveLabel = typename FluidModel<dim>::SolveLabel;

    /**
     * The other stages of a step, as a scheme may call them
     * (implemented by the Simulation).
     */
    class Stages
    {
    public:
      virtual ~Stages() = default;
      /// The sub-grid lubrication and the contact projection of
      /// @p predicted over a step @p dt from the current positions: the
      /// corrected translational velocities. A @p trial leaves no trace:
      /// the glue stays that of the start of the step, and its trouble is
      /// not reported (the step's final correction reports its own).
      virtual const std::vector<Vec3> &
      correct(PredictedVelocities &predicted, double dt, bool trial) = 0;
      /// The fluid model's rigid velocities at @p X under @p shear_rate.
      virtual Statistics
      solve_at(const std::vector<Vec3> &X,
               double                   shear_rate,
               const SolveLabel        &label,
               std::vector<Vec3>       &U,
               std::vector<Vec3>       &W) = 0;
      /// The fluid model's rigid velocities at the current positions and
      /// time, into the run state.
      virtual Statistics
      solve_at_current_positions() = 0;
    };

    virtual ~TimeScheme() = default;

    /// The velocities of the step of length @p dt from @p state.
    virtual void
    predict(const RunState      &state,
            double               dt,
            Stages              &stages,
            PredictedVelocities &predicted) = 0;

    /// The velocities at the positions the step reached (state.X, after
    /// the move), into state.U and state.W; the statistics of the
    /// solves of the step.
    virtual Statistics
    velocities_after_step(RunState &state, Stages &stages) = 0;
  };
} // namespace Fidus

#endif
