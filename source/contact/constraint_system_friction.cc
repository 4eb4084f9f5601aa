#include "coulomb_kernels.h"

#include <algorithm>
#include <cmath>
#include <fidus/contact/constraint_system.h>
#include <fidus/contact/vector_operations.h>
#include <limits>

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
  using namespace Coulomb;



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



  bool
  ConstraintSystem::stays_open(const std::size_t        k,
                               const double             rhs,
                               const std::vector<Vec3> &u) const
  {
    // Most rows of a packing are candidates that stay open; their exact
    // local solution is zero.
    return Coulomb::stays_open(glued_[k] != 0,
                               lambda_[k],
                               lambda_t_[k],
                               e_[k],
                               u[a_[k]],
                               u[b_[k]],
                               surface_a_[k],
                               rhs);
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
        const double w_n = inv_w[a_[k]] + inv_w[b_[k]];
        const double w_t = tangential_weight(k, inv_w, inv_j);
        if (stays_open(k, (gap_[k] - offset_[k]) / dt, u))
          continue;
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



  double
  ConstraintSystem::frictional_sweep(const bool                 forward,
                                     const double               mu,
                                     const std::vector<double> &w_t,
                                     const std::vector<double> &inv_w,
                                     const std::vector<double> &inv_j,
                                     std::vector<Vec3>         &u,
                                     std::vector<Vec3>         &w)
  {
    const std::size_t count  = size();
    double            change = 0.;
    for (std::size_t i = 0; i < count; ++i)
      {
        const std::size_t k = forward ? i : count - 1 - i;
        // Most rows stay open: test them on the arrays before gathering
        // the rest of the row.
        if (stays_open(k, rhs_[k], u))
          continue;
        change = std::max(change,
                          sweep_contact(sweep_row(k, w_t),
                                        mu,
                                        relaxation_,
                                        inv_w,
                                        inv_j,
                                        u,
                                        w,
                                        lambda_[k],
                                        lambda_t_[k]));
      }
    return change;
  }



  Coulomb::SweepRow
  ConstraintSystem::sweep_row(const std::size_t          k,
                              const std::vector<double> &w_t) const
  {
    return SweepRow{a_[k],
                    b_[k],
                    glued_[k] != 0,
                    lever_a_[k],
                    lever_b_[k],
                    rhs_[k],
                    diag_[k],
                    w_t[k],
                    e_[k],
                    surface_a_[k]};
  }



  double
  ConstraintSystem::active_frictional_sweeps(
    const std::vector<std::uint32_t> &rows,
    const double                      mu,
    const std::vector<double>        &w_t,
    const std::vector<double>        &inv_w,
    const std::vector<double>        &inv_j,
    const double                      dt,
    const double                      tolerance,
    std::vector<Vec3>                &u,
    std::vector<Vec3>                &w)
  {
    // The rows with an impulse are an eighth of a dense packing's rows,
    // scattered over arrays too large for the cache: sweeping them where
    // they lie costs a cache miss per array and row. They are gathered once
    // here and swept contiguously (doc/history/contact.md).
    const std::size_t     count = rows.size();
    std::vector<SweepRow> packed(count);
    std::vector<double>   lambda_n(count);
    std::vector<Vec3>     lambda_t(count);
    for (std::size_t i = 0; i < count; ++i)
      {
        packed[i]   = sweep_row(rows[i], w_t);
        lambda_n[i] = lambda_[rows[i]];
        lambda_t[i] = lambda_t_[rows[i]];
      }
    double change = 0.;
    for (unsigned int j = 0; j < active_sweeps; ++j)
      {
        change = 0.;
        for (std::size_t i = 0; i < count; ++i)
          {
            const std::size_t r = (j % 2 == 0) ? i : count - 1 - i;
            change              = std::max(change,
                              sweep_contact(packed[r],
                                            mu,
                                            relaxation_,
                                            inv_w,
                                            inv_j,
                                            u,
                                            w,
                                            lambda_n[r],
                                            lambda_t[r]));
          }
        if (change * dt <= tolerance)
          break;
      }
    for (std::size_t i = 0; i < count; ++i)
      {
        lambda_[rows[i]]   = lambda_n[i];
        lambda_t_[rows[i]] = lambda_t[i];
      }
    return change;
  }



  // When the Newton step is rejected (the stick and slip states it froze
  // are wrong for some contacts), the normal impulses take the
  // frictionless subspace step instead, with the tangential impulses
  // frozen: the normal problem is then the frictionless one for the
  // predicted velocities plus the tangential impulses' share (a normal
  // impulse does not turn a sphere, nor does a rotation move a contact
  // point normally), and the step decreases its dual objective. Without
  // it the sweeps can stall in dense 3D packings with more contacts than
  // particles (contact/friction).
  double
  ConstraintSystem::frictionless_fallback_step(const double             mu,
                                               const std::vector<Vec3> &u_star,
                                               const std::vector<double> &inv_w,
                                               const std::vector<double> &inv_j,
                                               const double               dt,
                                               const double       tolerance,
                                               std::vector<Vec3> &u,
                                               std::vector<Vec3> &w)
  {
    const Vec3        zero{{0., 0., 0.}};
    std::vector<Vec3> shifted = u_star;
    std::vector<Vec3> unused(w.size(), zero);
    for (std::size_t k = 0; k < size(); ++k)
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
    // Back into the cones of the new normal impulses (a row that the step
    // opened keeps no tangential impulse).
    for (std::size_t k = 0; k < size(); ++k)
      {
        const double radius = mu * std::max(lambda_[k], 0.);
        const double length = norm(lambda_t_[k]);
        if (length > radius)
          {
            Vec3 change;
            for (unsigned d = 0; d < 3; ++d)
              change[d] = (radius / length - 1.) * lambda_t_[k][d];
            add_impulse(k, 0., change, inv_w, inv_j, u, w);
            for (unsigned d = 0; d < 3; ++d)
              lambda_t_[k][d] = radius > 0. ? lambda_t_[k][d] + change[d] : 0.;
          }
      }
    return frictional_residual(mu, u, w, inv_w, inv_j, dt);
  }



  void
  ConstraintSystem::add_impulse(const std::size_t          k,
                                const double               dn,
                                const Vec3                &dt,
                                const std::vector<double> &inv_w,
                                const std::vector<double> &inv_j,
                                std::vector<Vec3>         &u,
                                std::vector<Vec3>         &w) const
  {
    scatter(u,
            w,
            a_[k],
            b_[k],
            e_[k],
            lever_a_[k],
            lever_b_[k],
            dn,
            dt,
            inv_w,
            inv_j);
  }



  // Where contacts stick in a jammed cluster at a large friction
  // coefficient, the exact local updates can cycle: a contact that one
  // neighbour's update makes slide is made to stick by the next, and the
  // residual stays at about 1e-5 for ever (a 1000-sphere packing at mu = 1,
  // doc/history/contact.md). Taking a fraction of each update breaks the
  // cycle, at the cost of a slower linear rate; so it is taken only after
  // a window of iterations without progress, and lowered step by step.
  void
  ConstraintSystem::relax_if_stalled(const double  residual,
                                     StallMonitor &monitor)
  {
    monitor.minimum = std::min(monitor.minimum, residual);
    if (++monitor.count < stall_window)
      return;
    if (monitor.minimum > stall_progress * monitor.previous_minimum)
      relaxation_ =
        std::max(minimum_relaxation, relaxation_factor * relaxation_);
    monitor.previous_minimum = monitor.minimum;
    monitor.minimum          = std::numeric_limits<double>::max();
    monitor.count            = 0;
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
        w_t[k]   = tangential_weight(k, inv_w, inv_j);
      }

    // The velocities of the stored multipliers; recomputed from them at
    // the end (as in solve()) so that what is returned satisfies
    // u = u* + W^-1 G^T lambda to round-off.
    auto apply_all = [&]() {
      u = u_star;
      w = w_star;
      for (std::size_t k = 0; k < m; ++k)
        add_impulse(k, lambda_[k], lambda_t_[k], inv_w, inv_j, u, w);
    };

    Result result;
    apply_all();
    result.residual = frictional_residual(mu, u, w, inv_w, inv_j, dt);

    std::vector<std::uint32_t> active;
    relaxation_ = 1.;
    StallMonitor monitor{result.residual, result.residual};

    while (result.residual > tolerance && result.iterations < max_iterations)
      {
        relax_if_stalled(result.residual, monitor);
        // Sweeps alternate direction, as in the frictionless Gauss-Seidel,
        // so that a chain of contacts is resolved as fast from either end.
        const bool forward = (result.iterations % 2 == 0);
        // The largest local change of the sweep, in the residual's units:
        // while it is above the tolerance, it stands for the residual,
        // whose evaluation costs most of a sweep.
        const double change =
          frictional_sweep(forward, mu, w_t, inv_w, inv_j, u, w);
        // Most rows of a dense packing are candidates that stay open; the
        // slow error is in the rows that carry an impulse. Sweeping those
        // alone until their own change is small costs a fraction of a full
        // sweep; the next full sweep finds the rows that open or close.
        active.clear();
        for (std::size_t k = 0; k < m; ++k)
          if (glued_[k] || lambda_[k] != 0.)
            active.push_back(k);
        if (change * dt > tolerance && 4 * active.size() < m)
          active_frictional_sweeps(active,
                                   mu,
                                   w_t,
                                   inv_w,
                                   inv_j,
                                   dt,
                                   tolerance,
                                   u,
                                   w);
        ++result.iterations;
        const bool subspace_due =
          subspace && result.iterations % sweeps_per_subspace_step == 0;
        result.residual = change * dt;
        if (result.residual <= tolerance || subspace_due)
          result.residual = frictional_residual(mu, u, w, inv_w, inv_j, dt);
        // The sweeps converge linearly, slowly where sliding and sticking
        // contacts hold the same particles and over the long-range
        // compression of a jammed packing; the Newton step on the contacts
        // with an impulse removes both errors
        // (constraint_system_friction_subspace.cc).
        if (subspace_due && result.residual > tolerance)
          {
            const double before = result.residual;
            result.residual     = frictional_subspace_step(mu,
                                                       u_star,
                                                       w_star,
                                                       inv_w,
                                                       inv_j,
                                                       dt,
                                                       tolerance,
                                                       result.residual,
                                                       u,
                                                       w);
            if (result.residual >= before)
              result.residual = frictionless_fallback_step(mu,
                                                           u_star,
                                                           inv_w,
                                                           inv_j,
                                                           dt,
                                                           tolerance,
                                                           u,
                                                           w);
          }
      }
    apply_all();
    result.residual   = frictional_residual(mu, u, w, inv_w, inv_j, dt);
    result.converged  = result.residual <= tolerance;
    result.relaxation = relaxation_;
    return result;
  }
} // namespace Fidus::Contact
