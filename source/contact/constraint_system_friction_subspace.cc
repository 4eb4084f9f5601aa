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
    /// What a contact contributes to the Newton system.
    enum class State
    {
      normal_only, ///< glued under tension: no friction
      stick,       ///< normal and tangential velocity zero
      slide        ///< normal velocity zero, impulse on the cone's rim
    };

    /// A contact of the subspace, its state and its tangent directions.
    struct SubspaceRow
    {
      std::uint32_t k;
      State         state;
      unsigned int  n_tangential; ///< tangential unknowns (0, 1 or 2)
      Vec3          t[2];         ///< directions of the tangential unknowns
      Vec3          d;            ///< slide: direction of the impulse
      double        kappa;        ///< slide: |v_t| / (mu lambda_n)
    };

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
    // A planar problem (2D: normals in the xy plane, rotations about z)
    // has one tangential direction: the out-of-plane one has no right-hand
    // side and couples with nothing in the plane, so leaving it out is
    // exact.
    bool planar = true;
    for (std::size_t p = 0; p < u_star.size() && planar; ++p)
      planar = u_star[p][2] == 0. && w_star[p][0] == 0. && w_star[p][1] == 0.;
    for (std::size_t k = 0; k < size() && planar; ++k)
      planar = e_[k][2] == 0.;

    std::vector<SubspaceRow> rows;
    std::vector<std::size_t> first(1, 0); // offset of each row's unknowns
    for (std::size_t k = 0; k < size(); ++k)
      {
        if (!glued_[k] && !(lambda_[k] > 0.))
          continue;
        SubspaceRow  row{static_cast<std::uint32_t>(k),
                        State::normal_only,
                        0,
                        {},
                        {},
                        0.};
        const double l_t = norm(lambda_t_[k]);
        // A scaled-back impulse lies on the rim to round-off.
        if (lambda_[k] > 0. && l_t < (1. - 1e-10) * mu * lambda_[k])
          {
            row.state        = State::stick;
            row.n_tangential = planar ? 1 : 2;
            row.t[0]         = perpendicular(e_[k]);
            row.t[1]         = cross(e_[k], row.t[0]);
          }
        else if (lambda_[k] > 0.)
          {
            row.state        = State::slide;
            row.n_tangential = planar ? 0 : 1;
            for (unsigned d = 0; d < 3; ++d)
              row.d[d] = lambda_t_[k][d] / l_t;
            row.t[0] = cross(e_[k], row.d);
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
                             rhs_[k],
                             c,
                             v_t);
            row.kappa = norm(v_t) / (mu * lambda_[k]);
          }
        rows.push_back(row);
        first.push_back(first.back() + 1 + row.n_tangential);
      }
    if (rows.empty())
      return residual_before;

    // The tangential impulse of x on row i.
    auto tangential = [&](const std::vector<double> &x, const std::size_t i) {
      const SubspaceRow &row = rows[i];
      Vec3               f{{0., 0., 0.}};
      const double      *y = &x[first[i]];
      if (row.state == State::stick)
        for (unsigned j = 0; j < row.n_tangential; ++j)
          for (unsigned d = 0; d < 3; ++d)
            f[d] += y[1 + j] * row.t[j][d];
      else if (row.state == State::slide)
        for (unsigned d = 0; d < 3; ++d)
          f[d] =
            mu * y[0] * row.d[d] + (row.n_tangential ? y[1] * row.t[0][d] : 0.);
      return f;
    };
    // The rows' equations for the velocities (uu, ww): with @p affine the
    // residual of the current state, otherwise the linear part.
    auto equations = [&](const std::vector<Vec3>   &uu,
                         const std::vector<Vec3>   &ww,
                         const bool                 affine,
                         std::vector<double>       &y,
                         const std::vector<double> *x) {
      for (std::size_t i = 0; i < rows.size(); ++i)
        {
          const SubspaceRow  &row = rows[i];
          const std::uint32_t k   = row.k;
          double              c;
          Vec3                v_t;
          contact_velocity(uu,
                           ww,
                           a_[k],
                           b_[k],
                           e_[k],
                           lever_a_[k],
                           lever_b_[k],
                           affine ? surface_a_[k] : Vec3{{0., 0., 0.}},
                           affine ? rhs_[k] : 0.,
                           c,
                           v_t);
          y[first[i]] = c;
          for (unsigned j = 0; j < row.n_tangential; ++j)
            y[first[i] + 1 + j] = dot(v_t, row.t[j]);
          // The slide row's own term; lambda_t.p = 0 in the current state.
          if (row.state == State::slide && row.n_tangential && x)
            y[first[i] + 1] += row.kappa * (*x)[first[i] + 1];
        }
    };
    std::vector<Vec3> v(u.size()), o(w.size());
    auto apply = [&](const std::vector<double> &x, std::vector<double> &y) {
      std::fill(v.begin(), v.end(), Vec3{{0., 0., 0.}});
      std::fill(o.begin(), o.end(), Vec3{{0., 0., 0.}});
      for (std::size_t i = 0; i < rows.size(); ++i)
        {
          const std::uint32_t k = rows[i].k;
          scatter(v,
                  o,
                  a_[k],
                  b_[k],
                  e_[k],
                  lever_a_[k],
                  lever_b_[k],
                  x[first[i]],
                  tangential(x, i),
                  inv_w,
                  inv_j);
        }
      equations(v, o, false, y, &x);
    };

    std::vector<double> b(first.back());
    equations(u, w, true, b, nullptr);
    for (double &bi : b)
      bi = -bi;
    // Right-preconditioned by the diagonal (W_n, W_t, W_t + kappa), which
    // puts the normal, sticking and sliding rows on one scale.
    std::vector<double> scale(b.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      {
        const std::uint32_t k   = rows[i].k;
        const double        w_n = inv_w[a_[k]] + inv_w[b_[k]];
        const double w_t = w_n + lever_a_[k] * lever_a_[k] * inv_j[a_[k]] +
                           lever_b_[k] * lever_b_[k] * inv_j[b_[k]];
        scale[first[i]] = 1. / w_n;
        for (unsigned j = 0; j < rows[i].n_tangential; ++j)
          scale[first[i] + 1 + j] = 1. / (w_t + rows[i].kappa);
      }
    std::vector<double> scaled(b.size());
    auto                preconditioned = [&](const std::vector<double> &y,
                              std::vector<double>       &z) {
      for (std::size_t i = 0; i < y.size(); ++i)
        scaled[i] = scale[i] * y[i];
      apply(scaled, z);
    };
    // An inexact Newton step: a linear residual of one hundredth of the
    // nonlinear one is enough while the latter is far above the tolerance.
    const double stop =
      std::max(0.1 * tolerance / dt, newton_forcing * max_abs(b));
    std::vector<double> delta =
      bicgstab(preconditioned, b, stop, max_cg_iterations);
    for (std::size_t i = 0; i < delta.size(); ++i)
      delta[i] *= scale[i];

    // Take the step, projected on the cones; halve it while it does not
    // lower the residual (the classification it assumed may be wrong for
    // a few contacts, which a shorter step disturbs less).
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
            double              l_n = old_n[i] + alpha * delta[first[i]];
            if (!glued_[k] && l_n < 0.)
              l_n = 0.;
            Vec3 l_t = tangential(delta, i);
            for (unsigned d = 0; d < 3; ++d)
              l_t[d] = old_t[i][d] + alpha * l_t[d];
            const double radius = mu * std::max(l_n, 0.), length = norm(l_t);
            if (length > radius ||
                (rows[i].state == State::slide && length > 0.))
              for (unsigned d = 0; d < 3; ++d)
                l_t[d] *= radius / length;
            Vec3 change_t;
            for (unsigned d = 0; d < 3; ++d)
              change_t[d] = l_t[d] - old_t[i][d];
            scatter(u,
                    w,
                    a_[k],
                    b_[k],
                    e_[k],
                    lever_a_[k],
                    lever_b_[k],
                    l_n - old_n[i],
                    change_t,
                    inv_w,
                    inv_j);
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
} // namespace Fidus::Contact
