#include "coulomb_kernels.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/constraint_system.h>
#include <fidus/contact/vector_operations.h>

// The subspace step of the frictional projection: a semi-smooth Newton step
// on the contacts that carry an impulse, with their stick or slip state
// frozen (doc/theory/contact.md, "Friction", "Solver").
//
// Why it is needed: the Gauss-Seidel sweeps solve each contact exactly with
// the others frozen, and a contact that slides couples its tangential
// impulse to its normal one (|lambda_t| = mu lambda_n). A particle held by
// one sticking and one sliding contact then passes the error back and forth
// between them, and the sweeps converge linearly at a rate set by mu, not by
// the size of the packing; the frictionless subspace step, which freezes the
// tangential impulses, cannot remove that error. The Newton step solves the
// coupled equations of all the contacts at once:
//
//   every contact with an impulse   normal velocity c = 0,
//   a sticking contact              tangential velocity v_t = 0,
//   a sliding contact               lambda_t = mu lambda_n d along its
//                                   direction d (opposite to the slip),
//                                   and in 3D the linearised turn of d:
//                                   v_t.p + kappa lambda_t.p = 0 with
//                                   p = e x d and kappa = |v_t|/(mu lambda_n)
//                                   (from lambda_t = -mu lambda_n v_t/|v_t|).
//
// The sliding rows make the system unsymmetric, so it is solved by
// BiCGStab, matrix-free like the frictionless step's conjugate gradients.
// The step is then projected on the cones (a sliding impulse back onto the
// rim) and kept only if it lowers the residual: the Coulomb problem has no
// objective that could test it, and a rejected step costs one residual.

namespace Fidus::Contact
{
  using namespace Coulomb;

  namespace
  {
    /// A unit vector perpendicular to @p e.
    Vec3
    perpendicular(const Vec3 &e)
    {
      Vec3 t = cross(e, Vec3{{0., 0., 1.}});
      if (norm(t) < 0.5)
        t = cross(e, Vec3{{1., 0., 0.}});
      const double l = norm(t);
      for (unsigned d = 0; d < 3; ++d)
        t[d] /= l;
      return t;
    }

    double
    dot_n(const std::vector<double> &x, const std::vector<double> &y)
    {
      double z = 0.;
      for (std::size_t i = 0; i < x.size(); ++i)
        z += x[i] * y[i];
      return z;
    }

    double
    max_abs(const std::vector<double> &x)
    {
      double z = 0.;
      for (const double xi : x)
        z = std::max(z, std::abs(xi));
      return z;
    }

    /**
     * BiCGStab for A x = b from x = 0, stopped when the largest residual
     * entry is below @p stop or after @p max_iterations.
     */
    template <typename Operator>
    std::vector<double>
    bicgstab(const Operator            &apply,
             const std::vector<double> &b,
             const double               stop,
             const unsigned int         max_iterations)
    {
      const std::size_t   n = b.size();
      std::vector<double> x(n, 0.), r = b, r0 = b, p(n, 0.), v(n, 0.), s(n),
                                    t(n);
      double rho = 1., alpha = 1., omega = 1.;
      for (unsigned int j = 0; j < max_iterations && max_abs(r) > stop; ++j)
        {
          const double rho_new = dot_n(r0, r);
          if (rho_new == 0. || omega == 0.)
            break;
          const double beta = rho_new / rho * alpha / omega;
          rho               = rho_new;
          for (std::size_t i = 0; i < n; ++i)
            p[i] = r[i] + beta * (p[i] - omega * v[i]);
          apply(p, v);
          const double r0v = dot_n(r0, v);
          if (r0v == 0.)
            break;
          alpha = rho / r0v;
          for (std::size_t i = 0; i < n; ++i)
            s[i] = r[i] - alpha * v[i];
          if (max_abs(s) <= stop)
            {
              for (std::size_t i = 0; i < n; ++i)
                x[i] += alpha * p[i];
              break;
            }
          apply(s, t);
          const double tt = dot_n(t, t);
          omega           = tt > 0. ? dot_n(t, s) / tt : 0.;
          for (std::size_t i = 0; i < n; ++i)
            {
              x[i] += alpha * p[i] + omega * s[i];
              r[i] = s[i] - omega * t[i];
            }
        }
      return x;
    }
  } // namespace


  /// What a contact contributes to the Newton system.
  enum class ConstraintSystem::NewtonState
  {
    normal_only, ///< glued under tension: no friction
    stick,       ///< normal and tangential velocity zero
    slide        ///< normal velocity zero, impulse on the cone's rim
  };

  /// A contact of the Newton system, its state and its tangent directions.
  struct ConstraintSystem::NewtonRow
  {
    std::uint32_t k;
    NewtonState   state;
    unsigned int  n_tangential; ///< tangential unknowns (0, 1 or 2)
    std::size_t   offset;       ///< index of its normal unknown
    Vec3          t[2];         ///< directions of the tangential unknowns
    Vec3          d;            ///< slide: direction of the impulse
    double        kappa;        ///< slide: |v_t| / (mu lambda_n)
    // The contact's geometry, copied from the system's arrays: the Krylov
    // solver applies the operator tens of times per step, and reads it
    // here in row order instead of at the scattered index k among several
    // times more open rows, a cache miss per array (doc/history/contact.md).
    std::uint32_t a;       ///< first body
    std::uint32_t b;       ///< second body
    Vec3          e;       ///< unit normal from a to b
    double        lever_a; ///< a's contact point at +lever_a e
    double        lever_b; ///< b's contact point at -lever_b e

    /// The tangential impulse of the unknowns @p x on this contact.
    Vec3
    tangential(const std::vector<double> &x, const double mu) const
    {
      Vec3          f{{0., 0., 0.}};
      const double *y = &x[offset];
      if (state == NewtonState::stick)
        for (unsigned j = 0; j < n_tangential; ++j)
          for (unsigned c = 0; c < 3; ++c)
            f[c] += y[1 + j] * t[j][c];
      else if (state == NewtonState::slide)
        for (unsigned c = 0; c < 3; ++c)
          f[c] = mu * y[0] * d[c] + (n_tangential ? y[1] * t[0][c] : 0.);
      return f;
    }
  };



  void
  ConstraintSystem::row_velocity(const std::size_t        k,
                                 const std::vector<Vec3> &u,
                                 const std::vector<Vec3> &w,
                                 const bool               affine,
                                 double                  &c,
                                 Vec3                    &v_t) const
  {
    contact_velocity(u,
                     w,
                     a_[k],
                     b_[k],
                     e_[k],
                     lever_a_[k],
                     lever_b_[k],
                     affine ? surface_a_[k] : Vec3{{0., 0., 0.}},
                     affine ? rhs_[k] : 0.,
                     c,
                     v_t);
  }



  std::vector<ConstraintSystem::NewtonRow>
  ConstraintSystem::newton_rows(const double             mu,
                                const std::vector<Vec3> &u_star,
                                const std::vector<Vec3> &w_star,
                                const std::vector<Vec3> &u,
                                const std::vector<Vec3> &w) const
  {
    // A planar problem (2D: normals in the xy plane, rotations about z)
    // has one tangential direction: the out-of-plane one has no right-hand
    // side and couples with nothing in the plane, so leaving it out is
    // exact.
    bool planar = true;
    for (std::size_t p = 0; p < u_star.size() && planar; ++p)
      planar = u_star[p][2] == 0. && w_star[p][0] == 0. && w_star[p][1] == 0.;
    for (std::size_t k = 0; k < size() && planar; ++k)
      planar = e_[k][2] == 0.;

    std::vector<NewtonRow> rows;
    std::size_t            offset = 0;
    for (std::size_t k = 0; k < size(); ++k)
      {
        if (!glued_[k] && !(lambda_[k] > 0.))
          continue;
        NewtonRow    row{static_cast<std::uint32_t>(k),
                      NewtonState::normal_only,
                      0,
                      offset,
                      {},
                      {},
                      0.,
                      a_[k],
                      b_[k],
                      e_[k],
                      lever_a_[k],
                      lever_b_[k]};
        const double l_t = norm(lambda_t_[k]);
        // A scaled-back impulse lies on the rim to round-off.
        if (lambda_[k] > 0. && l_t < (1. - 1e-10) * mu * lambda_[k])
          {
            row.state        = NewtonState::stick;
            row.n_tangential = planar ? 1 : 2;
            row.t[0]         = perpendicular(e_[k]);
            row.t[1]         = cross(e_[k], row.t[0]);
          }
        else if (lambda_[k] > 0.)
          {
            row.state        = NewtonState::slide;
            row.n_tangential = planar ? 0 : 1;
            for (unsigned d = 0; d < 3; ++d)
              row.d[d] = lambda_t_[k][d] / l_t;
            row.t[0] = cross(e_[k], row.d);
            double c;
            Vec3   v_t;
            row_velocity(k, u, w, true, c, v_t);
            row.kappa = norm(v_t) / (mu * lambda_[k]);
          }
        rows.push_back(row);
        offset += 1 + row.n_tangential;
      }
    return rows;
  }



  std::vector<double>
  ConstraintSystem::newton_direction(const std::vector<NewtonRow> &rows,
                                     const double                  mu,
                                     const std::vector<double>    &inv_w,
                                     const std::vector<double>    &inv_j,
                                     const double                  dt,
                                     const double                  tolerance,
                                     const std::vector<Vec3>      &u,
                                     const std::vector<Vec3>      &w) const
  {
    const std::size_t n = rows.back().offset + 1 + rows.back().n_tangential;
    // The rows' equations for the velocities (uu, ww): with @p x null the
    // residual of the current state, otherwise the linear part for the
    // unknowns x.
    auto equations = [&](const std::vector<Vec3>   &uu,
                         const std::vector<Vec3>   &ww,
                         const std::vector<double> *x,
                         std::vector<double>       &y) {
      const Vec3 zero{{0., 0., 0.}};
      for (const NewtonRow &row : rows)
        {
          double c;
          Vec3   v_t;
          contact_velocity(uu,
                           ww,
                           row.a,
                           row.b,
                           row.e,
                           row.lever_a,
                           row.lever_b,
                           x ? zero : surface_a_[row.k],
                           x ? 0. : rhs_[row.k],
                           c,
                           v_t);
          y[row.offset] = c;
          for (unsigned j = 0; j < row.n_tangential; ++j)
            y[row.offset + 1 + j] = dot(v_t, row.t[j]);
          // The slide row's own term; lambda_t.p = 0 in the current state.
          if (row.state == NewtonState::slide && row.n_tangential && x)
            y[row.offset + 1] += row.kappa * (*x)[row.offset + 1];
        }
    };
    // y = G_S W^{-1} G_S^T x, matrix-free, as in the frictionless step.
    std::vector<Vec3> v(u.size()), o(w.size());
    auto apply = [&](const std::vector<double> &x, std::vector<double> &y) {
      std::fill(v.begin(), v.end(), Vec3{{0., 0., 0.}});
      std::fill(o.begin(), o.end(), Vec3{{0., 0., 0.}});
      for (const NewtonRow &row : rows)
        scatter(v,
                o,
                row.a,
                row.b,
                row.e,
                row.lever_a,
                row.lever_b,
                x[row.offset],
                row.tangential(x, mu),
                inv_w,
                inv_j);
      equations(v, o, &x, y);
    };

    std::vector<double> b(n);
    equations(u, w, nullptr, b);
    for (double &bi : b)
      bi = -bi;
    // Right-preconditioned by the diagonal (W_n, W_t, W_t + kappa), which
    // puts the normal, sticking and sliding rows on one scale.
    std::vector<double> scale(n);
    for (const NewtonRow &row : rows)
      {
        scale[row.offset] = 1. / (inv_w[a_[row.k]] + inv_w[b_[row.k]]);
        for (unsigned j = 0; j < row.n_tangential; ++j)
          scale[row.offset + 1 + j] =
            1. / (tangential_weight(row.k, inv_w, inv_j) + row.kappa);
      }
    std::vector<double> scaled(n);
    auto                preconditioned = [&](const std::vector<double> &y,
                              std::vector<double>       &z) {
      for (std::size_t i = 0; i < n; ++i)
        scaled[i] = scale[i] * y[i];
      apply(scaled, z);
    };
    // An inexact Newton step: a linear residual of one hundredth of the
    // nonlinear one is enough while the latter is far above the tolerance.
    const double stop =
      std::max(0.1 * tolerance / dt, newton_forcing * max_abs(b));
    std::vector<double> delta =
      bicgstab(preconditioned, b, stop, max_cg_iterations);
    for (std::size_t i = 0; i < n; ++i)
      delta[i] *= scale[i];
    return delta;
  }



  double
  ConstraintSystem::take_newton_step(const std::vector<NewtonRow> &rows,
                                     const std::vector<double>    &delta,
                                     const double                  mu,
                                     const std::vector<double>    &inv_w,
                                     const std::vector<double>    &inv_j,
                                     const double                  dt,
                                     const double       residual_before,
                                     std::vector<Vec3> &u,
                                     std::vector<Vec3> &w)
  {
    // The step projected on the cones; halved while it does not lower the
    // residual (the classification it assumed may be wrong for a few
    // contacts, which a shorter step disturbs less).
    const std::vector<Vec3> old_u = u, old_w = w;
    std::vector<double>     old_n(rows.size());
    std::vector<Vec3>       old_t(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      {
        old_n[i] = lambda_[rows[i].k];
        old_t[i] = lambda_t_[rows[i].k];
      }
    double alpha = 1.;
    for (unsigned int attempt = 0; attempt < newton_attempts;
         ++attempt, alpha *= 0.5)
      {
        if (attempt > 0)
          {
            u = old_u;
            w = old_w;
          }
        for (std::size_t i = 0; i < rows.size(); ++i)
          {
            const std::uint32_t k   = rows[i].k;
            double              l_n = old_n[i] + alpha * delta[rows[i].offset];
            if (!glued_[k] && l_n < 0.)
              l_n = 0.;
            Vec3 l_t = rows[i].tangential(delta, mu);
            for (unsigned d = 0; d < 3; ++d)
              l_t[d] = old_t[i][d] + alpha * l_t[d];
            const double radius = mu * std::max(l_n, 0.), length = norm(l_t);
            if (length > radius ||
                (rows[i].state == NewtonState::slide && length > 0.))
              for (unsigned d = 0; d < 3; ++d)
                l_t[d] *= radius / length;
            Vec3 change_t;
            for (unsigned d = 0; d < 3; ++d)
              change_t[d] = l_t[d] - old_t[i][d];
            add_impulse(k, l_n - old_n[i], change_t, inv_w, inv_j, u, w);
            lambda_[k]   = l_n;
            lambda_t_[k] = l_t;
          }
        const double residual = frictional_residual(mu, u, w, inv_w, inv_j, dt);
        if (residual < residual_before)
          return residual;
      }
    u = old_u;
    w = old_w;
    for (std::size_t i = 0; i < rows.size(); ++i)
      {
        lambda_[rows[i].k]   = old_n[i];
        lambda_t_[rows[i].k] = old_t[i];
      }
    return residual_before;
  }



  double
  ConstraintSystem::frictional_subspace_step(const double               mu,
                                             const std::vector<Vec3>   &u_star,
                                             const std::vector<Vec3>   &w_star,
                                             const std::vector<double> &inv_w,
                                             const std::vector<double> &inv_j,
                                             const double               dt,
                                             const double       tolerance,
                                             const double       residual_before,
                                             std::vector<Vec3> &u,
                                             std::vector<Vec3> &w)
  {
    const std::vector<NewtonRow> rows = newton_rows(mu, u_star, w_star, u, w);
    if (rows.empty())
      return residual_before;
    const std::vector<double> delta =
      newton_direction(rows, mu, inv_w, inv_j, dt, tolerance, u, w);
    return take_newton_step(rows,
                            delta,
                            mu,
                            inv_w,
                            inv_j,
                            dt,
                            residual_before,
                            u,
                            w);
  }
} // namespace Fidus::Contact
