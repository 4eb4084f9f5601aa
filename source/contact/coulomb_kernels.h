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
} // namespace Fidus::Contact::Coulomb

#endif
