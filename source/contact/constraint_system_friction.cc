#include <algorithm>
#include <cmath>
#include <fidus/contact/constraint_system.h>
#include <fidus/contact/vector_operations.h>

// Coulomb friction in the projection (doc/theory/contact.md, "Friction"):
// the non-smooth block Gauss-Seidel method of Moreau and Jean, with the
// exact solution of each contact's local problem.
//
// Why a closed form is exact here: the metric is diagonal per body (an
// isolated particle's translational and rotational resistance), and a
// sphere's contact point moves normally only with its centre. So a
// contact's local Delassus block is diag(W_n, W_t, W_t): the normal and the
// tangential impulses do not couple within the block, and Coulomb's law
// for one contact is solved by taking lambda_n first and then the stick
// impulse, scaled back onto the cone's rim when it lies outside (sliding,
// with the impulse opposite to the slip). That is the exact law, not the
// convex relaxation of Anitescu and Tasora, which would open every sliding
// contact at mu |v_t|.

namespace Fidus::Contact
{
  namespace
  {
    /// One contact's impulse.
    struct Impulse
    {
      double n = 0.;
      Vec3   t = {{0., 0., 0.}};
    };

    /**
     * The relative velocity at the contact point, v_b - v_a, split into its
     * normal constraint value c = (D - offset)/dt + v.e and its tangential
     * part v_t (in-plane in 2D, where omega has a z component only).
     */
    inline void
    contact_velocity(const std::vector<Vec3> &u,
                     const std::vector<Vec3> &w,
                     const std::uint32_t      a,
                     const std::uint32_t      b,
                     const Vec3              &e,
                     const double             lever_a,
                     const double             lever_b,
                     const Vec3              &surface_a,
                     const double             rhs,
                     double                  &c,
                     Vec3                    &v_t)
    {
      // Surface of a at +lever_a e, surface of b at -lever_b e.
      const Vec3 wa = cross(w[a], e), wb = cross(w[b], e);
      Vec3       v;
      for (unsigned d = 0; d < 3; ++d)
        v[d] =
          u[b][d] - lever_b * wb[d] - u[a][d] - lever_a * wa[d] - surface_a[d];
      const double vn = v[0] * e[0] + v[1] * e[1] + v[2] * e[2];
      c               = rhs + vn;
      for (unsigned d = 0; d < 3; ++d)
        v_t[d] = v[d] - vn * e[d];
    }

    /**
     * Exact Coulomb law for one contact with the others frozen: the free
     * velocities q are what the contact would have without its own
     * impulse; glued rows take any normal impulse, and only a compressive
     * one (lambda_n > 0) carries friction.
     */
    inline Impulse
    local_solution(const double   c,
                   const Vec3    &v_t,
                   const Impulse &old,
                   const double   w_n,
                   const double   w_t,
                   const bool     glued,
                   const double   mu)
    {
      Impulse      r;
      const double q_n = c - w_n * old.n;
      r.n              = -q_n / w_n;
      if (!glued && r.n < 0.)
        r.n = 0.;
      Vec3 q_t;
      for (unsigned d = 0; d < 3; ++d)
        q_t[d] = v_t[d] - w_t * old.t[d];
      const double radius = mu * std::max(r.n, 0.);
      const double slip   = norm(q_t);
      // Stick when the impulse that stops the slip lies in the cone.
      const double scale = (slip <= w_t * radius) ? 1. / w_t : radius / slip;
      for (unsigned d = 0; d < 3; ++d)
        r.t[d] = -scale * q_t[d];
      return r;
    }

    /// Add the impulse change (dn e + dt) on the second body, its opposite
    /// on the first, to the velocities and angular velocities.
    inline void
    scatter(std::vector<Vec3>         &u,
            std::vector<Vec3>         &w,
            const std::uint32_t        a,
            const std::uint32_t        b,
            const Vec3                &e,
            const double               lever_a,
            const double               lever_b,
            const double               dn,
            const Vec3                &dt,
            const std::vector<double> &inv_w,
            const std::vector<double> &inv_j)
    {
      for (unsigned d = 0; d < 3; ++d)
        {
          const double f = dn * e[d] + dt[d];
          u[a][d] -= inv_w[a] * f;
          u[b][d] += inv_w[b] * f;
        }
      // Torque on b: (-lever_b e) x dt; on a: (lever_a e) x (-dt).
      const Vec3 ext = cross(e, dt);
      for (unsigned d = 0; d < 3; ++d)
        {
          w[a][d] -= lever_a * inv_j[a] * ext[d];
          w[b][d] -= lever_b * inv_j[b] * ext[d];
        }
    }
  } // namespace



  void
  ConstraintSystem::local_coulomb(const std::size_t        k,
                                  const double             mu,
                                  const double             w_n,
                                  const double             w_t,
                                  const double             rhs,
                                  const std::vector<Vec3> &u,
                                  const std::vector<Vec3> &w,
                                  double                  &n,
                                  Vec3                    &t) const
  {
    double c;
    Vec3   v_t;
    contact_velocity(u,
                     w,
                     a_[k],
                     b_[k],
                     e_[k],
                     lever_a_[k],
                     lever_b_[k],
                     surface_a_[k],
                     rhs,
                     c,
                     v_t);
    const Impulse next = local_solution(c,
                                        v_t,
                                        Impulse{lambda_[k], lambda_t_[k]},
                                        w_n,
                                        w_t,
                                        glued_[k] != 0,
                                        mu);
    n                  = next.n;
    t                  = next.t;
  }



  double
  ConstraintSystem::frictional_residual(const double               mu,
                                        const std::vector<Vec3>   &u,
                                        const std::vector<Vec3>   &w,
                                        const std::vector<double> &inv_w,
                                        const std::vector<double> &inv_j,
                                        const double               dt) const
  {
    double r = 0.;
    for (std::size_t k = 0; k < size(); ++k)
      {
        const std::uint32_t a = a_[k], b = b_[k];
        const double        w_n = inv_w[a] + inv_w[b];
        const double        w_t = w_n + lever_a_[k] * lever_a_[k] * inv_j[a] +
                           lever_b_[k] * lever_b_[k] * inv_j[b];
        const Impulse old{lambda_[k], lambda_t_[k]};
        Impulse       next;
        local_coulomb(k,
                      mu,
                      w_n,
                      w_t,
                      (gap_[k] - offset_[k]) / dt,
                      u,
                      w,
                      next.n,
                      next.t);
        Vec3 change;
        for (unsigned d = 0; d < 3; ++d)
          change[d] = next.t[d] - old.t[d];
        r = std::max({r, w_n * std::abs(next.n - old.n), w_t * norm(change)});
      }
    return r * dt;
  }



  ConstraintSystem::Result
  ConstraintSystem::solve_frictional(const double               mu,
                                     const std::vector<Vec3>   &u_star,
                                     const std::vector<Vec3>   &w_star,
                                     const std::vector<double> &inv_w,
                                     const std::vector<double> &inv_j,
                                     const double               dt,
                                     const double               tolerance,
                                     const unsigned int         max_iterations,
                                     const bool                 subspace,
                                     std::vector<Vec3>         &u,
                                     std::vector<Vec3>         &w)
  {
    const std::size_t m = size();
    rhs_.resize(m);
    diag_.resize(m);
    std::vector<double> w_t(m);
    for (std::size_t k = 0; k < m; ++k)
      {
        rhs_[k]  = (gap_[k] - offset_[k]) / dt;
        diag_[k] = inv_w[a_[k]] + inv_w[b_[k]];
        w_t[k]   = diag_[k] + lever_a_[k] * lever_a_[k] * inv_j[a_[k]] +
                 lever_b_[k] * lever_b_[k] * inv_j[b_[k]];
      }

    // The velocities of the stored multipliers; recomputed from them at
    // the end (as in solve()) so that what is returned satisfies
    // u = u* + W^-1 G^T lambda to round-off.
    const Vec3 zero{{0., 0., 0.}};
    auto       apply_all = [&]() {
      u = u_star;
      w = w_star;
      for (std::size_t k = 0; k < m; ++k)
        scatter(u,
                w,
                a_[k],
                b_[k],
                e_[k],
                lever_a_[k],
                lever_b_[k],
                lambda_[k],
                lambda_t_[k],
                inv_w,
                inv_j);
    };

    Result result;
    apply_all();
    result.residual = frictional_residual(mu, u, w, inv_w, inv_j, dt);

    while (result.residual > tolerance && result.iterations < max_iterations)
      {
        // Sweeps alternate direction, as in the frictionless Gauss-Seidel,
        // so that a chain of contacts is resolved as fast from either end.
        const bool forward = (result.iterations % 2 == 0);
        // The largest local change of the sweep, in the residual's units:
        // while it is above the tolerance, it stands for the residual,
        // whose evaluation costs most of a sweep.
        double change = 0.;
        for (std::size_t i = 0; i < m; ++i)
          {
            const std::size_t   k = forward ? i : m - 1 - i;
            const std::uint32_t a = a_[k], b = b_[k];
            const Impulse       old{lambda_[k], lambda_t_[k]};
            Impulse             next;
            local_coulomb(k,
                          mu,
                          diag_[k],
                          w_t[k],
                          rhs_[k],
                          u,
                          w,
                          next.n,
                          next.t);
            Vec3 dt_change;
            for (unsigned d = 0; d < 3; ++d)
              dt_change[d] = next.t[d] - old.t[d];
            const double dn_change = next.n - old.n;
            change                 = std::max({change,
                                               diag_[k] * std::abs(dn_change),
                                               w_t[k] * norm(dt_change)});
            if (dn_change != 0. || dt_change != zero)
              {
                lambda_[k]   = next.n;
                lambda_t_[k] = next.t;
                scatter(u,
                        w,
                        a,
                        b,
                        e_[k],
                        lever_a_[k],
                        lever_b_[k],
                        dn_change,
                        dt_change,
                        inv_w,
                        inv_j);
              }
          }
        ++result.iterations;
        const bool subspace_due =
          subspace && result.iterations % sweeps_per_subspace_step == 0;
        result.residual = change * dt;
        if (result.residual <= tolerance || subspace_due)
          result.residual = frictional_residual(mu, u, w, inv_w, inv_j, dt);
        if (subspace_due && result.residual > tolerance)
          {
            // The sweeps converge like Gauss-Seidel, in O(L^2) sweeps for
            // the long-range compression of a jammed packing. That error is
            // in the normal impulses, and with the tangential ones frozen
            // the normal problem is the frictionless one for the predicted
            // velocities plus the tangential impulses' share (a normal
            // impulse does not turn a sphere, nor does a rotation move a
            // contact point normally): the frictionless subspace step
            // applies to it unchanged, and decreases its dual objective.
            std::vector<Vec3> shifted = u_star;
            std::vector<Vec3> unused(w.size(), zero);
            for (std::size_t k = 0; k < m; ++k)
              scatter(shifted,
                      unused,
                      a_[k],
                      b_[k],
                      e_[k],
                      0.,
                      0.,
                      0.,
                      lambda_t_[k],
                      inv_w,
                      inv_j);
            subspace_step(shifted, inv_w, dt, tolerance, u);
            result.residual = frictional_residual(mu, u, w, inv_w, inv_j, dt);
          }
      }
    apply_all();
    result.residual  = frictional_residual(mu, u, w, inv_w, inv_j, dt);
    result.converged = result.residual <= tolerance;
    return result;
  }
} // namespace Fidus::Contact
