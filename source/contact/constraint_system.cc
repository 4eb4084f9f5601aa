#include <algorithm>
#include <cmath>
#include <fidus/contact/constraint_system.h>

namespace Fidus::Contact
{
  namespace
  {
    /// (u_b - u_a) . e, the normal relative velocity of a row.
    inline double
    relative_normal_velocity(const std::vector<Vec3> &u,
                             const std::uint32_t      a,
                             const std::uint32_t      b,
                             const Vec3              &e)
    {
      return (u[b][0] - u[a][0]) * e[0] + (u[b][1] - u[a][1]) * e[1] +
             (u[b][2] - u[a][2]) * e[2];
    }

    /// u_b += s_b e, u_a -= s_a e: the action of W^{-1} G^T on one row.
    inline void
    scatter(std::vector<Vec3>         &u,
            const std::uint32_t        a,
            const std::uint32_t        b,
            const Vec3                &e,
            const double               delta,
            const std::vector<double> &inv_w)
    {
      const double sa = inv_w[a] * delta, sb = inv_w[b] * delta;
      for (unsigned d = 0; d < 3; ++d)
        {
          u[a][d] -= sa * e[d];
          u[b][d] += sb * e[d];
        }
    }
  } // namespace



  void
  ConstraintSystem::clear()
  {
    a_.clear();
    b_.clear();
    e_.clear();
    gap_.clear();
    glued_.clear();
    lambda_.clear();
    gamma_.clear();
    rhs_.clear();
    diag_.clear();
    offset_.clear();
    lever_a_.clear();
    lever_b_.clear();
    lambda_t_.clear();
    surface_a_.clear();
  }



  void
  ConstraintSystem::reserve(const std::size_t n)
  {
    a_.reserve(n);
    b_.reserve(n);
    e_.reserve(n);
    gap_.reserve(n);
    glued_.reserve(n);
    lambda_.reserve(n);
    gamma_.reserve(n);
    offset_.reserve(n);
    lever_a_.reserve(n);
    lever_b_.reserve(n);
    lambda_t_.reserve(n);
    surface_a_.reserve(n);
  }



  void
  ConstraintSystem::add_row(const std::uint32_t a,
                            const std::uint32_t b,
                            const Vec3         &e,
                            const double        gap,
                            const bool          glued,
                            const double        lambda,
                            const double        gamma)
  {
    a_.push_back(a);
    b_.push_back(b);
    e_.push_back(e);
    gap_.push_back(gap);
    glued_.push_back(glued ? 1 : 0);
    // A warm start must be admissible for the dual problem.
    lambda_.push_back(glued ? lambda : std::max(lambda, 0.));
    gamma_.push_back(gamma);
    offset_.push_back(0.);
    lever_a_.push_back(0.);
    lever_b_.push_back(0.);
    lambda_t_.push_back(Vec3{{0., 0., 0.}});
    surface_a_.push_back(Vec3{{0., 0., 0.}});
  }



  void
  ConstraintSystem::set_contact_geometry(const double lever_a,
                                         const double lever_b,
                                         const double offset,
                                         const Vec3  &surface_velocity_a)
  {
    lever_a_.back()   = lever_a;
    lever_b_.back()   = lever_b;
    offset_.back()    = offset;
    surface_a_.back() = surface_velocity_a;
  }



  void
  ConstraintSystem::apply_multipliers(const std::vector<Vec3>   &u_star,
                                      const std::vector<double> &inv_w,
                                      std::vector<Vec3>         &u) const
  {
    u = u_star;
    for (std::size_t k = 0; k < size(); ++k)
      if (lambda_[k] != 0.)
        scatter(u, a_[k], b_[k], e_[k], lambda_[k], inv_w);
  }



  double
  ConstraintSystem::residual(const std::vector<Vec3> &u, const double dt) const
  {
    double r = 0.;
    for (std::size_t k = 0; k < size(); ++k)
      {
        const double c = (gap_[k] - offset_[k]) / dt +
                         relative_normal_velocity(u, a_[k], b_[k], e_[k]);
        double rk;
        if (glued_[k])
          rk = std::abs(c);
        else if (diag_.size() == size())
          rk = std::abs(std::min(diag_[k] * lambda_[k], c));
        else
          rk = lambda_[k] > 0. ? std::abs(c) : std::max(-c, 0.);
        r = std::max(r, rk);
      }
    return r * dt;
  }



  double
  ConstraintSystem::gershgorin_bound(const std::vector<double> &inv_w,
                                     const std::size_t          n_bodies) const
  {
    // |A_kl| <= inv_w of the shared body (|e_k . e_l| <= 1), so a row sum of
    // |A| is at most inv_w_a n_a + inv_w_b n_b with n_p the number of rows
    // that touch body p: an upper bound of lambda_max(A), which makes any
    // step rho < 2 / bound safe for projected gradient.
    std::vector<unsigned int> count(n_bodies, 0);
    for (std::size_t k = 0; k < size(); ++k)
      {
        ++count[a_[k]];
        ++count[b_[k]];
      }
    double bound = 0.;
    for (std::size_t k = 0; k < size(); ++k)
      bound =
        std::max(bound,
                 inv_w[a_[k]] * count[a_[k]] + inv_w[b_[k]] * count[b_[k]]);
    return bound;
  }



  ConstraintSystem::Result
  ConstraintSystem::solve(const DualSolver           solver,
                          const std::vector<Vec3>   &u_star,
                          const std::vector<double> &inv_w,
                          const double               dt,
                          const double               tolerance,
                          const unsigned int         max_iterations,
                          std::vector<Vec3>         &u)
  {
    rhs_.resize(size());
    diag_.resize(size());
    for (std::size_t k = 0; k < size(); ++k)
      {
        rhs_[k]  = (gap_[k] - offset_[k]) / dt;
        diag_[k] = inv_w[a_[k]] + inv_w[b_[k]];
      }

    // The iterations update u incrementally; the velocities returned are
    // recomputed from the multipliers so that u = u* + W^{-1} G^T lambda
    // holds to round-off, and the residual is that of exactly what is
    // returned. If the round-off of the incremental updates hid a residual
    // above the tolerance, iterate again from the recomputed velocities.
    Result result;
    for (int round = 0; round < 4; ++round)
      {
        const unsigned int done = result.iterations;
        if (done >= max_iterations && round > 0)
          break;
        result = solve_with(solver,
                            u_star,
                            inv_w,
                            dt,
                            tolerance,
                            max_iterations - done,
                            u);
        result.iterations += done;
        apply_multipliers(u_star, inv_w, u);
        result.residual  = residual(u, dt);
        result.converged = result.residual <= tolerance;
        if (result.converged)
          break;
      }
    return result;
  }



  ConstraintSystem::Result
  ConstraintSystem::solve_with(const DualSolver           solver,
                               const std::vector<Vec3>   &u_star,
                               const std::vector<double> &inv_w,
                               const double               dt,
                               const double               tolerance,
                               const unsigned int         max_iterations,
                               std::vector<Vec3>         &u)
  {
    Result result;
    switch (solver)
      {
        case DualSolver::projected_gauss_seidel:
          result = solve_gauss_seidel(u_star,
                                      inv_w,
                                      dt,
                                      tolerance,
                                      max_iterations,
                                      false,
                                      u);
          break;
        case DualSolver::projected_gauss_seidel_subspace:
          result = solve_gauss_seidel(u_star,
                                      inv_w,
                                      dt,
                                      tolerance,
                                      max_iterations,
                                      true,
                                      u);
          break;
        case DualSolver::accelerated_projected_gradient:
          result = solve_projected_gradient(u_star,
                                            inv_w,
                                            dt,
                                            tolerance,
                                            max_iterations,
                                            true,
                                            u);
          break;
        case DualSolver::projected_gradient:
        default:
          result = solve_projected_gradient(u_star,
                                            inv_w,
                                            dt,
                                            tolerance,
                                            max_iterations,
                                            false,
                                            u);
          break;
      }
    return result;
  }



  ConstraintSystem::Result
  ConstraintSystem::solve_gauss_seidel(const std::vector<Vec3>   &u_star,
                                       const std::vector<double> &inv_w,
                                       const double               dt,
                                       const double               tolerance,
                                       const unsigned int max_iterations,
                                       const bool         subspace,
                                       std::vector<Vec3> &u)
  {
    // Projected Gauss-Seidel on the dual: row by row, solve exactly for
    // lambda_k with the others frozen (c_k = 0), project on lambda_k >= 0 for
    // unglued rows, and update the two velocities it touches. One sweep costs
    // as much as one matrix-vector product, and information travels along a
    // chain of contacts within one sweep instead of one row per iteration.
    // Sweeps alternate direction (symmetric Gauss-Seidel) so that a chain is
    // resolved as fast from either end.
    Result result;
    apply_multipliers(u_star, inv_w, u);
    result.residual     = residual(u, dt);
    const std::size_t m = size();
    while (result.residual > tolerance && result.iterations < max_iterations)
      {
        const bool forward = (result.iterations % 2 == 0);
        for (std::size_t i = 0; i < m; ++i)
          {
            const std::size_t   k = forward ? i : m - 1 - i;
            const std::uint32_t a = a_[k], b = b_[k];
            const Vec3         &e = e_[k];
            const double c = rhs_[k] + relative_normal_velocity(u, a, b, e);
            double       l = lambda_[k] - c / diag_[k];
            if (!glued_[k] && l < 0.)
              l = 0.;
            const double delta = l - lambda_[k];
            if (delta != 0.)
              {
                lambda_[k] = l;
                scatter(u, a, b, e, delta, inv_w);
              }
          }
        ++result.iterations;
        result.residual = residual(u, dt);
        if (subspace && result.residual > tolerance &&
            result.iterations % sweeps_per_subspace_step == 0)
          {
            subspace_step(u_star, inv_w, dt, tolerance, u);
            result.residual = residual(u, dt);
          }
      }
    result.converged = result.residual <= tolerance;
    return result;
  }



  double
  ConstraintSystem::dual_objective(const std::vector<Vec3>   &u_star,
                                   const std::vector<double> &inv_w,
                                   const std::vector<Vec3>   &u) const
  {
    // f(lambda) = 1/2 lambda^T A lambda + b^T lambda with
    // lambda^T A lambda = |u - u*|_W^2 and b = D/dt + G u*.
    double f = 0.;
    for (std::size_t p = 0; p < u.size(); ++p)
      if (inv_w[p] > 0.)
        for (unsigned d = 0; d < 3; ++d)
          f += 0.5 * (u[p][d] - u_star[p][d]) * (u[p][d] - u_star[p][d]) /
               inv_w[p];
    for (std::size_t k = 0; k < size(); ++k)
      if (lambda_[k] != 0.)
        f += lambda_[k] *
             (rhs_[k] + relative_normal_velocity(u_star, a_[k], b_[k], e_[k]));
    return f;
  }



  void
  ConstraintSystem::subspace_step(const std::vector<Vec3>   &u_star,
                                  const std::vector<double> &inv_w,
                                  const double               dt,
                                  const double               tolerance,
                                  std::vector<Vec3>         &u)
  {
    // Gauss-Seidel removes the local error fast but needs O(L^2) sweeps for
    // the smooth, long-range error of a jammed packing of diameter L (the
    // force network carries a compression across the whole packing). Once
    // the sweeps have found which rows are active (glued, or lambda > 0),
    // that error lives in the subspace of the active rows, where the problem
    // is the linear system A_SS delta = -c_S; conjugate gradients solve it
    // matrix-free in O(sqrt(cond)) products. The step is then projected on
    // lambda >= 0 and kept only if it lowers the dual objective, otherwise
    // it is cut at the first bound it hits (on that segment the convex
    // objective cannot increase). Every step therefore decreases the dual
    // objective, like the sweeps, so the combination keeps converging.
    const std::size_t        m = size();
    std::vector<std::size_t> active;
    active.reserve(m);
    for (std::size_t k = 0; k < m; ++k)
      if (glued_[k] || lambda_[k] > 0.)
        active.push_back(k);
    const std::size_t s = active.size();
    if (s == 0)
      return;

    std::vector<double> r(s), p(s), q(s), delta(s, 0.);
    std::vector<Vec3>   v(u.size());
    double              rr = 0.;
    for (std::size_t i = 0; i < s; ++i)
      {
        const std::size_t k = active[i];
        r[i] = -(rhs_[k] + relative_normal_velocity(u, a_[k], b_[k], e_[k]));
        p[i] = r[i];
        rr += r[i] * r[i];
      }
    const double stop = 0.1 * tolerance / dt;
    for (unsigned int j = 0; j < max_cg_iterations; ++j)
      {
        // q = A_SS p = G_S W^{-1} G_S^T p, matrix-free.
        std::fill(v.begin(), v.end(), Vec3{{0., 0., 0.}});
        for (std::size_t i = 0; i < s; ++i)
          {
            const std::size_t k = active[i];
            scatter(v, a_[k], b_[k], e_[k], p[i], inv_w);
          }
        double pq = 0.;
        for (std::size_t i = 0; i < s; ++i)
          {
            const std::size_t k = active[i];
            q[i] = relative_normal_velocity(v, a_[k], b_[k], e_[k]);
            pq += p[i] * q[i];
          }
        if (!(pq > 0.))
          break;
        const double alpha  = rr / pq;
        double       rr_new = 0., r_max = 0.;
        for (std::size_t i = 0; i < s; ++i)
          {
            delta[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            rr_new += r[i] * r[i];
            r_max = std::max(r_max, std::abs(r[i]));
          }
        if (r_max <= stop)
          break;
        const double beta = rr_new / rr;
        rr                = rr_new;
        for (std::size_t i = 0; i < s; ++i)
          p[i] = r[i] + beta * p[i];
      }

    const double        f_old = dual_objective(u_star, inv_w, u);
    std::vector<double> old_lambda(s);
    for (std::size_t i = 0; i < s; ++i)
      old_lambda[i] = lambda_[active[i]];
    const std::vector<Vec3> old_u = u;

    // Try the projected full step.
    for (std::size_t i = 0; i < s; ++i)
      {
        const std::size_t k = active[i];
        double            l = old_lambda[i] + delta[i];
        if (!glued_[k] && l < 0.)
          l = 0.;
        const double change = l - lambda_[k];
        lambda_[k]          = l;
        scatter(u, a_[k], b_[k], e_[k], change, inv_w);
      }
    if (dual_objective(u_star, inv_w, u) <= f_old)
      return;

    // Otherwise cut the step at the first bound.
    double alpha_max = 1.;
    for (std::size_t i = 0; i < s; ++i)
      if (!glued_[active[i]] && delta[i] < 0.)
        alpha_max = std::min(alpha_max, -old_lambda[i] / delta[i]);
    u = old_u;
    for (std::size_t i = 0; i < s; ++i)
      {
        const std::size_t k = active[i];
        double            l = old_lambda[i] + alpha_max * delta[i];
        if (!glued_[k] && l < 0.)
          l = 0.;
        lambda_[k] = l;
        scatter(u, a_[k], b_[k], e_[k], l - old_lambda[i], inv_w);
      }
  }



  ConstraintSystem::Result
  ConstraintSystem::solve_projected_gradient(const std::vector<Vec3>   &u_star,
                                             const std::vector<double> &inv_w,
                                             const double               dt,
                                             const double       tolerance,
                                             const unsigned int max_iterations,
                                             const bool         accelerated,
                                             std::vector<Vec3> &u)
  {
    // Projected gradient (Uzawa) on the dual: lambda <- P(lambda - rho c).
    // The gradient c(lambda) = b + A lambda is evaluated matrix-free through
    // u = u* + W^{-1} G^T lambda. Plain Uzawa uses rho = 1.9 / bound
    // (< 2 / lambda_max(A), see gershgorin_bound()); the accelerated variant
    // (Nesterov/FISTA) needs rho <= 1 / lambda_max and restarts its momentum
    // whenever the step goes against the previous one (adaptive restart),
    // which keeps it monotone-ish on the many nearly singular directions of
    // a packing.
    Result            result;
    const std::size_t m        = size();
    const std::size_t n_bodies = u_star.size();
    const double      bound    = gershgorin_bound(inv_w, n_bodies);
    if (m == 0 || bound <= 0.)
      {
        apply_multipliers(u_star, inv_w, u);
        result.residual = residual(u, dt);
        return result;
      }
    const double rho = (accelerated ? 1.0 : 1.9) / bound;

    std::vector<double> lambda_prev(lambda_), y(m), c(m);
    std::vector<Vec3>   u_prev, u_y(n_bodies);
    apply_multipliers(u_star, inv_w, u);
    u_prev   = u;
    double t = 1.;

    while (true)
      {
        result.residual = residual(u, dt);
        if (result.residual <= tolerance || result.iterations >= max_iterations)
          break;
        ++result.iterations;

        double beta = 0., t_next = 1.;
        if (accelerated)
          {
            t_next = 0.5 * (1. + std::sqrt(1. + 4. * t * t));
            beta   = (t - 1.) / t_next;
          }
        // Extrapolated point y and its velocities (linear in lambda).
        for (std::size_t k = 0; k < m; ++k)
          y[k] = lambda_[k] + beta * (lambda_[k] - lambda_prev[k]);
        for (std::size_t p = 0; p < n_bodies; ++p)
          for (unsigned d = 0; d < 3; ++d)
            u_y[p][d] = u[p][d] + beta * (u[p][d] - u_prev[p][d]);

        // Projected step from y; restart test (y - new).(new - lambda) > 0.
        double restart = 0.;
        for (std::size_t k = 0; k < m; ++k)
          {
            c[k] = rhs_[k] + relative_normal_velocity(u_y, a_[k], b_[k], e_[k]);
            double l = y[k] - rho * c[k];
            if (!glued_[k] && l < 0.)
              l = 0.;
            restart += (y[k] - l) * (l - lambda_[k]);
            c[k] = l; // c now holds the new multipliers
          }
        lambda_prev.swap(lambda_);
        u_prev.swap(u);
        u = u_y;
        for (std::size_t k = 0; k < m; ++k)
          {
            lambda_[k]         = c[k];
            const double delta = c[k] - y[k];
            if (delta != 0.)
              scatter(u, a_[k], b_[k], e_[k], delta, inv_w);
          }
        t = (accelerated && restart <= 0.) ? t_next : 1.;
      }
    result.converged = result.residual <= tolerance;
    return result;
  }
} // namespace Fidus::Contact
