#include <cmath>
#include <fidus/simulation/run_state.h>
#include <fidus/time_stepping/adams_bashforth.h>
#include <fidus/time_stepping/trapezoidal_scheme.h>
#include <string>

namespace Fidus
{
  template <int dim>
  TrapezoidalScheme<dim>::TrapezoidalScheme(
    const ShearRate        &shear_rate,
    const BoxGeometry<dim> &box_geometry,
    const bool              with_forces,
    const bool              follows_shear,
    const unsigned int      n_passes)
    : shear(shear_rate)
    , box(box_geometry)
    , forced(with_forces)
    , boundary_follows_shear(follows_shear)
    , passes(n_passes)
  {}



  template <int dim>
  void
  TrapezoidalScheme<dim>::predict(const RunState      &state,
                                  const double         dt,
                                  Stages              &stages,
                                  PredictedVelocities &predicted)
  {
    AdamsBashforth2<dim>::extrapolate(state,
                                      dt,
                                      shear,
                                      forced,
                                      predicted.u,
                                      predicted.w);
    predicted.middle.clear();
    // The trapezoidal rule X+ = X + dt (U(X) + U(X+)) / 2 is symmetric in
    // time: run backwards from X+ with the reversed shear, it gives back X
    // exactly. X+ is found by fixed-point iteration from the AB2
    // prediction: each pass solves the fluid at the positions the current
    // velocities reach, and averages. The contraction factor is
    // dt |grad U| / 2, so one pass (a predictor-corrector) leaves an error
    // of O(dt^4) per step. The last pass's velocities also serve as those
    // at the end of the step (velocities_after_step() does not solve
    // again): they were solved O(dt^3) away from X+, which changes the next
    // step by O(dt^4) as well, and keeps the cost of one pass that of AB2.
    //
    // With the shear rate g(t), U = g V(X) at fixed positions. Both ends
    // are solved with the shear rate of their time (the end's solve is the
    // next step's start, and its stress belongs to that time) and rescaled
    // to the rate of the middle of the step, as in the AB2 extrapolation:
    // a jump of g at a step boundary (a reversal) then stays exact. A zero
    // rate at either end, external forces and a boundary that does not
    // follow g take the plain mean.
    const double g_now  = shear(state.time);
    const double g_mid  = shear(state.time + 0.5 * dt);
    const double g_end  = shear(state.time + dt);
    const bool   scaled = !forced && boundary_follows_shear &&
                        std::abs(g_now) > 0. && std::abs(g_end) > 0.;
    const double c_now = scaled ? g_mid / g_now : 1.;
    const double c_end = scaled ? g_mid / g_end : 1.;
    const typename TimeScheme<dim>::SolveLabel label{
      state.step + 1,
      "step " + std::to_string(state.step + 1) +
        " (trapezoidal corrector, end of the step " +
        "from t = " + std::to_string(state.time) + ")"};

    const unsigned int n = state.X.size();
    std::vector<Vec3>  X_end(n);
    U_end.resize(n);
    W_end.resize(n);
    pass_statistics = Statistics();
    have_end        = false;
    for (unsigned int pass = 0; pass < passes; ++pass)
      {
        const std::vector<Vec3> &u_corrected =
          stages.correct(predicted, dt, true);
        predicted.middle.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            {
              const double step = d < dim ? dt * u_corrected[i][d] : 0.;
              X_end[i][d]       = state.X[i][d] + step;
              // Not wrapped: the contact module takes minimum images of
              // separations, and a step is far shorter than a period.
              predicted.middle[i][d] = state.X[i][d] + 0.5 * step;
            }
        box.wrap(X_end);

        // The step's row reports the last pass's solve, with the
        // iterations of all passes and their largest rigidity residual.
        pass_statistics = pass_statistics.followed_by(
          stages.solve_at(X_end, g_end, label, U_end, W_end));
        have_end = true;

        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            {
              predicted.u[i][d] =
                0.5 * (c_now * state.U[i][d] + c_end * U_end[i][d]);
              predicted.w[i][d] =
                0.5 * (c_now * state.W[i][d] + c_end * W_end[i][d]);
            }
      }
  }



  template <int dim>
  typename TrapezoidalScheme<dim>::Statistics
  TrapezoidalScheme<dim>::velocities_after_step(RunState &state, Stages &stages)
  {
    if (!have_end)
      return stages.solve_at_current_positions();
    // The trapezoidal passes of this step solved the fluid last (see
    // predict()); the row reports all of their iterations, and the
    // model's fields are those of the last.
    have_end = false;
    state.U  = U_end;
    state.W  = W_end;
    return pass_statistics;
  }



  template class TrapezoidalScheme<2>;
  template class TrapezoidalScheme<3>;
} // namespace Fidus
