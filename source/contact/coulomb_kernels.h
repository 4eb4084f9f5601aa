#ifndef fidus_contact_coulomb_kernels_h
#define fidus_contact_coulomb_kernels_h

// The per-contact pieces of the frictional projection, shared by its
// Gauss-Seidel sweeps (constraint_system_friction.cc) and its subspace step
// (constraint_system_friction_subspace.cc). Internal to the contact module.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <fidus/contact/vector_operations.h>
#include <vector>

namespace Fidus::Contact::Coulomb
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

  /**
   * Whether a contact carries no impulse and keeps none: its exact local
   * solution is then zero. The normal velocity needs neither the rotations
   * (they move a contact point tangentially) nor the tangential part.
   */
  inline bool
  stays_open(const bool   glued,
             const double lambda_n,
             const Vec3  &lambda_t,
             const Vec3  &e,
             const Vec3  &ua,
             const Vec3  &ub,
             const Vec3  &s,
             const double rhs)
  {
    const Vec3 &t = lambda_t;
    if (glued || lambda_n != 0. || t[0] != 0. || t[1] != 0. || t[2] != 0.)
      return false;
    return rhs + (ub[0] - ua[0] - s[0]) * e[0] + (ub[1] - ua[1] - s[1]) * e[1] +
             (ub[2] - ua[2] - s[2]) * e[2] >=
           0.;
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

  /// One contact's data for the Gauss-Seidel sweeps, stored contiguously.
  struct SweepRow
  {
    std::uint32_t a;       ///< first body
    std::uint32_t b;       ///< second body
    bool          glued;   ///< glued: any normal impulse
    double        lever_a; ///< a's contact point at +lever_a e
    double        lever_b; ///< b's contact point at -lever_b e
    double        rhs;     ///< gap term (D - offset) / dt
    double        w_n;     ///< normal Delassus entry
    double        w_t;     ///< tangential Delassus entry
    Vec3          e;       ///< unit normal from a to b
    Vec3          surface; ///< a's surface velocity (a wall)
  };

  /**
   * One contact's step of a frictional Gauss-Seidel sweep: its exact local
   * Coulomb solution with the others frozen (only the fraction
   * @p relaxation of the way when that is below 1), the impulse
   * (@p lambda_n, @p lambda_t) and the velocities updated. Returns the
   * unrelaxed change max(W_n |d lambda_n|, W_t |d lambda_t|).
   */
  inline double
  sweep_contact(const SweepRow            &row,
                const double               mu,
                const double               relaxation,
                const std::vector<double> &inv_w,
                const std::vector<double> &inv_j,
                std::vector<Vec3>         &u,
                std::vector<Vec3>         &w,
                double                    &lambda_n,
                Vec3                      &lambda_t)
  {
    if (stays_open(row.glued,
                   lambda_n,
                   lambda_t,
                   row.e,
                   u[row.a],
                   u[row.b],
                   row.surface,
                   row.rhs))
      return 0.;
    const Impulse old{lambda_n, lambda_t};
    double        c;
    Vec3          v_t;
    contact_velocity(u,
                     w,
                     row.a,
                     row.b,
                     row.e,
                     row.lever_a,
                     row.lever_b,
                     row.surface,
                     row.rhs,
                     c,
                     v_t);
    Impulse next = local_solution(c, v_t, old, row.w_n, row.w_t, row.glued, mu);
    Vec3    dt_change;
    for (unsigned d = 0; d < 3; ++d)
      dt_change[d] = next.t[d] - old.t[d];
    double       dn_change = next.n - old.n;
    const double change =
      std::max(row.w_n * std::abs(dn_change), row.w_t * norm(dt_change));
    // A convex combination of two impulses in the cone stays in it.
    if (relaxation < 1.)
      {
        dn_change *= relaxation;
        next.n = old.n + dn_change;
        for (unsigned d = 0; d < 3; ++d)
          {
            dt_change[d] *= relaxation;
            next.t[d] = old.t[d] + dt_change[d];
          }
      }
    if (dn_change != 0. || dt_change[0] != 0. || dt_change[1] != 0. ||
        dt_change[2] != 0.)
      {
        lambda_n = next.n;
        lambda_t = next.t;
        scatter(u,
                w,
                row.a,
                row.b,
                row.e,
                row.lever_a,
                row.lever_b,
                dn_change,
                dt_change,
                inv_w,
                inv_j);
      }
    return change;
  }
} // namespace Fidus::Contact::Coulomb

#endif
