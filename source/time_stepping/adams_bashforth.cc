#include <cmath>
#include <fidus/simulation/run_state.h>
#include <fidus/time_stepping/adams_bashforth.h>

namespace Fidus
{
  template <int dim>
  AdamsBashforth2<dim>::AdamsBashforth2(const ShearRate &shear_rate,
                                        const bool       with_forces)
    : shear(shear_rate)
    , forced(with_forces)
  {}



  template <int dim>
  void
  AdamsBashforth2<dim>::extrapolate(const RunState    &s,
                                    const double       dt,
                                    const ShearRate   &shear,
                                    const bool         forced,
                                    std::vector<Vec3> &u,
                                    std::vector<Vec3> &w)
  {
    // The Stokes problem is quasi-static and linear in the boundary data,
    // so U is the shear rate times a field that depends on the positions
    // only. Extrapolating U / shear and multiplying by the shear rate at
    // the middle of the step is the same formula for a constant shear
    // rate, and stays exact when the shear rate jumps at a step boundary (a
    // reversal 't < T ? 1 : -1'), where plain AB2 would make one step with
    // -2U: an O(dt) error that breaks the reversibility of Stokes flow,
    // which is what the contact models are meant to keep.
    const double beta  = s.have_history ? dt / (2. * s.dt_old) : 0.;
    const double g_now = shear(s.time);
    const double g_old = s.have_history ? shear(s.t_old) : g_now;
    const double g_mid = shear(s.time + 0.5 * dt);
    // External forces add a part that does not scale with the shear rate.
    const bool scaled = !forced && std::abs(g_now) > 0. && std::abs(g_old) > 0.;
    const double       c_now = scaled ? g_mid / g_now : 1.;
    const double       c_old = scaled ? g_mid / g_old : 1.;
    const unsigned int n     = s.X.size();
    u.resize(n);
    w.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        {
          u[i][d] =
            (1. + beta) * c_now * s.U[i][d] - beta * c_old * s.U_old[i][d];
          w[i][d] =
            (1. + beta) * c_now * s.W[i][d] - beta * c_old * s.W_old[i][d];
        }
  }



  template <int dim>
  void
  AdamsBashforth2<dim>::predict(const RunState      &state,
                                const double         dt,
                                Stages              &stages,
                                PredictedVelocities &predicted)
  {
    (void)stages;
    extrapolate(state, dt, shear, forced, predicted.u, predicted.w);
    predicted.middle.clear();
  }



  template <int dim>
  typename AdamsBashforth2<dim>::Statistics
  AdamsBashforth2<dim>::velocities_after_step(RunState &state, Stages &stages)
  {
    (void)state;
    return stages.solve_at_current_positions();
  }



  template class AdamsBashforth2<2>;
  template class AdamsBashforth2<3>;
} // namespace Fidus
