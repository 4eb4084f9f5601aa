#ifndef fidus_contact_constraint_system_h
#define fidus_contact_constraint_system_h

#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <vector>

namespace Fidus::Contact
{
  namespace Coulomb
  {
    struct SweepRow;
  }

  /**
   * The linearised constraints of one projection and the solvers of its dual
   * problem (numerics section 3).
   *
   * Bodies are the particles 0..N-1 followed by the walls N..N+W-1; a wall is
   * a body with zero inverse weight (no degrees of freedom) and a prescribed
   * tangential velocity, so that particle-particle and particle-wall rows are
   * the same code. Row k couples bodies a_k and b_k with unit normal e_k
   * pointing from a_k to b_k and reads, in velocity units,
   *
   *   c_k(u) = D_k / dt + (u_b - u_a) . e_k  >= 0   (unglued),   = 0 (glued).
   *
   * With G the matrix of the rows, the KKT conditions of
   * min 1/2 |v - u*|_W^2 on K are u = u* + W^{-1} G^T lambda, lambda_k >= 0
   * and lambda_k c_k = 0 on unglued rows, c_k = 0 on glued rows. Eliminating u
   * gives the dual problem: minimise 1/2 lambda^T A lambda + b^T lambda,
   * A = G W^{-1} G^T, b = D/dt + G u*, subject to lambda_k >= 0 on unglued
   * rows; its gradient is c(lambda). All three solvers work matrix-free on
   * the rows: A is never formed.
   *
   * With Coulomb friction (solve_frictional()) each row also carries a
   * tangential impulse lambda_t, perpendicular to e_k, and the bodies turn:
   * the velocity of a body's surface at the contact point is u + omega x r
   * with r = +lever_a e (first body) or -lever_b e (second body). See
   * doc/theory/contact.md, "Friction".
   */
  class ConstraintSystem
  {
  public:
    /// Outcome of a solve.
    struct Result
    {
      unsigned int iterations = 0;
      double       residual   = 0.; ///< KKT residual, length units
      bool         converged  = false;
      /// Frictional solve: the smallest relaxation of the local updates
      /// that it had to take (1: none; solve_frictional()).
      double relaxation = 1.;
    };

    /// Remove all rows.
    void
    clear();

    /// Reserve memory for @p n rows.
    void
    reserve(std::size_t n);

    /**
     * Add row (a, b): gap @p gap, unit normal @p e from a to b, @p glued for
     * an equality row, initial multiplier @p lambda (warm start; it is
     * clipped to >= 0 on unglued rows) and glue variable @p gamma.
     */
    void
    add_row(std::uint32_t a,
            std::uint32_t b,
            const Vec3   &e,
            double        gap,
            bool          glued,
            double        lambda,
            double        gamma);

    /**
     * The geometry that only friction needs, for the row added last: the
     * distances @p lever_a and @p lever_b from the bodies' centres to the
     * contact point (the radii; 0 for a wall), and the contact distance
     * @p offset (rough contact): the row then holds D - offset >= 0 rather
     * than D >= 0, while gap() still returns the true gap D.
     * @p surface_velocity_a is a velocity of the first body's surface at
     * the contact point on top of its rigid motion (a wall whose velocity
     * varies along it, such as a z wall in linear shear); it must be
     * tangential, and only friction sees it.
     */
    void
    set_contact_geometry(double      lever_a,
                         double      lever_b,
                         double      offset,
                         const Vec3 &surface_velocity_a = {{0., 0., 0.}});

    /**
     * Solve the frictional problem: the rows as in solve(), and for every
     * row a tangential impulse in Coulomb's cone |lambda_t| <= mu
     * max(lambda_n, 0) that opposes the slip when the contact slides and
     * stops it when the cone allows (exact Coulomb law, no relaxation).
     * Non-smooth block Gauss-Seidel with the exact local solution of each
     * contact (solve_frictional() in constraint_system_friction.cc).
     *
     * @p w_star are the predicted angular velocities (z component only in
     * 2D), @p inv_j the inverse rotational weights (0 for walls); @p u and
     * @p w receive the corrected velocities of all bodies. The normal
     * multipliers start from those stored in the rows, the tangential ones
     * from zero. With @p mu = 0 the result is the frictionless projection
     * and the rotations are untouched. With @p subspace, every few sweeps
     * the normal impulses take the frictionless subspace step with the
     * tangential impulses frozen (see the implementation).
     */
    Result
    solve_frictional(double                     mu,
                     const std::vector<Vec3>   &u_star,
                     const std::vector<Vec3>   &w_star,
                     const std::vector<double> &inv_w,
                     const std::vector<double> &inv_j,
                     double                     dt,
                     double                     tolerance,
                     unsigned int               max_iterations,
                     bool                       subspace,
                     std::vector<Vec3>         &u,
                     std::vector<Vec3>         &w);

    /**
     * Residual of the frictional problem for velocities @p u, @p w with the
     * stored multipliers, in length units: dt times the largest change the
     * exact local solution of one contact would make to its relative
     * velocity, max(W_n |lambda_n' - lambda_n|, W_t |lambda_t' - lambda_t|).
     * Zero exactly at a solution of the Coulomb problem; without friction
     * it equals residual().
     */
    double
    frictional_residual(double                     mu,
                        const std::vector<Vec3>   &u,
                        const std::vector<Vec3>   &w,
                        const std::vector<double> &inv_w,
                        const std::vector<double> &inv_j,
                        double                     dt) const;

    /**
     * Solve the dual problem with @p solver, starting from the multipliers
     * stored in the rows, and write the corrected velocities of all bodies
     * into @p u (walls keep u*). @p inv_w holds 1/w per body (0 for walls).
     * Stops when residual() <= @p tolerance or after @p max_iterations
     * iterations (sweeps for Gauss-Seidel); never throws on non-convergence.
     */
    Result
    solve(DualSolver                 solver,
          const std::vector<Vec3>   &u_star,
          const std::vector<double> &inv_w,
          double                     dt,
          double                     tolerance,
          unsigned int               max_iterations,
          std::vector<Vec3>         &u);

    /**
     * KKT residual of velocities @p u with the stored multipliers, in length
     * units (times dt): the maximum over rows of dt |c_k| on glued rows and
     * dt |min(A_kk lambda_k, c_k)| on unglued rows. It is zero exactly when u
     * is feasible and complementarity holds, so it bounds both the constraint
     * violation and the slack of rows that still push.
     */
    double
    residual(const std::vector<Vec3> &u, double dt) const;

    /// Number of rows.
    std::size_t
    size() const
    {
      return gap_.size();
    }

    /// First body of row k (coefficient -e).
    std::uint32_t
    first(const std::size_t k) const
    {
      return a_[k];
    }

    /// Second body of row k (coefficient +e).
    std::uint32_t
    second(const std::size_t k) const
    {
      return b_[k];
    }

    /// Unit normal of row k, from first to second.
    const Vec3 &
    normal(const std::size_t k) const
    {
      return e_[k];
    }

    /// Gap D_k at the start of the step.
    double
    gap(const std::size_t k) const
    {
      return gap_[k];
    }

    /// Contact distance of row k (0 unless contact is rough).
    double
    offset(const std::size_t k) const
    {
      return offset_[k];
    }

    /// Distance from the first body's centre to the contact point.
    double
    lever_first(const std::size_t k) const
    {
      return lever_a_[k];
    }

    /// Distance from the second body's centre to the contact point.
    double
    lever_second(const std::size_t k) const
    {
      return lever_b_[k];
    }

    /// Tangential impulse of row k (zero without friction), acting on the
    /// second body (the first receives its opposite), perpendicular to e_k.
    const Vec3 &
    tangential_impulse(const std::size_t k) const
    {
      return lambda_t_[k];
    }

    /// Whether row k is an equality (glued pair).
    bool
    glued(const std::size_t k) const
    {
      return glued_[k] != 0;
    }

    /// Multiplier of row k.
    double
    lambda(const std::size_t k) const
    {
      return lambda_[k];
    }

    /// Glue variable of row k at the start of the step.
    double
    gamma(const std::size_t k) const
    {
      return gamma_[k];
    }

  private:
    void
    apply_multipliers(const std::vector<Vec3>   &u_star,
                      const std::vector<double> &inv_w,
                      std::vector<Vec3>         &u) const;

    Result
    solve_with(DualSolver                 solver,
               const std::vector<Vec3>   &u_star,
               const std::vector<double> &inv_w,
               double                     dt,
               double                     tolerance,
               unsigned int               max_iterations,
               std::vector<Vec3>         &u);

    double
    gershgorin_bound(const std::vector<double> &inv_w,
                     std::size_t                n_bodies) const;

    Result
    solve_projected_gradient(const std::vector<Vec3>   &u_star,
                             const std::vector<double> &inv_w,
                             double                     dt,
                             double                     tolerance,
                             unsigned int               max_iterations,
                             bool                       accelerated,
                             std::vector<Vec3>         &u);

    Result
    solve_gauss_seidel(const std::vector<Vec3>   &u_star,
                       const std::vector<double> &inv_w,
                       double                     dt,
                       double                     tolerance,
                       unsigned int               max_iterations,
                       bool                       subspace,
                       std::vector<Vec3>         &u);

    /**
     * Coulomb's law for row @p k alone, the other rows' impulses frozen:
     * the exact solution (@p n, @p t) for velocities @p u, @p w, local
     * block diag(@p w_n, @p w_t, @p w_t) and gap term @p rhs.
     */
    void
    local_coulomb(std::size_t              k,
                  double                   mu,
                  double                   w_n,
                  double                   w_t,
                  double                   rhs,
                  const std::vector<Vec3> &u,
                  const std::vector<Vec3> &w,
                  double                  &n,
                  Vec3                    &t) const;

    /// Conjugate-gradient step on the rows that are currently active.
    void
    subspace_step(const std::vector<Vec3>   &u_star,
                  const std::vector<double> &inv_w,
                  double                     dt,
                  double                     tolerance,
                  std::vector<Vec3>         &u);

    /**
     * One Gauss-Seidel sweep of the frictional problem over all rows, in
     * order or backwards: each contact takes its exact local Coulomb
     * solution with the others frozen (moved only the fraction
     * relaxation_ towards it when that is below 1), and @p u, @p w follow.
     * Returns the largest local change, max(W_n |d lambda_n|,
     * W_t |d lambda_t|), of the unrelaxed update; @p w_t holds the W_t.
     */
    double
    frictional_sweep(bool                       forward,
                     double                     mu,
                     const std::vector<double> &w_t,
                     const std::vector<double> &inv_w,
                     const std::vector<double> &inv_j,
                     std::vector<Vec3>         &u,
                     std::vector<Vec3>         &w);

    /**
     * Up to active_sweeps sweeps, alternating in direction, over the rows
     * listed in @p rows alone (gathered contiguously first), stopped when
     * a sweep's largest change times @p dt is at most @p tolerance.
     * Returns the last sweep's largest change.
     */
    double
    active_frictional_sweeps(const std::vector<std::uint32_t> &rows,
                             double                            mu,
                             const std::vector<double>        &w_t,
                             const std::vector<double>        &inv_w,
                             const std::vector<double>        &inv_j,
                             double                            dt,
                             double                            tolerance,
                             std::vector<Vec3>                &u,
                             std::vector<Vec3>                &w);

    /// Row @p k's data for the sweeps (coulomb_kernels.h), W_t from @p w_t.
    Coulomb::SweepRow
    sweep_row(std::size_t k, const std::vector<double> &w_t) const;

    /// Whether row @p k carries no impulse and its exact local solution,
    /// with normal right-hand side @p rhs, leaves it so (velocities @p u).
    bool
    stays_open(std::size_t k, double rhs, const std::vector<Vec3> &u) const;

    /**
     * The frictional Newton step (constraint_system_friction_subspace.cc):
     * on the contacts that carry an impulse, with their stick or slip state
     * frozen, the direction from newton_direction(), projected on the cones
     * and kept, whole or halved, if the residual falls below
     * @p residual_before. Returns the residual after the step.
     */
    double
    frictional_subspace_step(double                     mu,
                             const std::vector<Vec3>   &u_star,
                             const std::vector<Vec3>   &w_star,
                             const std::vector<double> &inv_w,
                             const std::vector<double> &inv_j,
                             double                     dt,
                             double                     tolerance,
                             double                     residual_before,
                             std::vector<Vec3>         &u,
                             std::vector<Vec3>         &w);

    enum class NewtonState;
    struct NewtonRow;

    /// The contacts of the Newton step, their states and unknowns.
    std::vector<NewtonRow>
    newton_rows(double                   mu,
                const std::vector<Vec3> &u_star,
                const std::vector<Vec3> &w_star,
                const std::vector<Vec3> &u,
                const std::vector<Vec3> &w) const;

    /// The Newton direction for @p rows at (u, w): BiCGStab, inexact.
    std::vector<double>
    newton_direction(const std::vector<NewtonRow> &rows,
                     double                        mu,
                     const std::vector<double>    &inv_w,
                     const std::vector<double>    &inv_j,
                     double                        dt,
                     double                        tolerance,
                     const std::vector<Vec3>      &u,
                     const std::vector<Vec3>      &w) const;

    /// Take the step @p delta, projected on the cones, whole or halved if
    /// that lowers the residual; otherwise leave everything as it was.
    double
    take_newton_step(const std::vector<NewtonRow> &rows,
                     const std::vector<double>    &delta,
                     double                        mu,
                     const std::vector<double>    &inv_w,
                     const std::vector<double>    &inv_j,
                     double                        dt,
                     double                        residual_before,
                     std::vector<Vec3>            &u,
                     std::vector<Vec3>            &w);

    /**
     * The frictionless subspace step on the normal impulses with the
     * tangential ones frozen, then every tangential impulse put back into
     * its new cone; the fallback of a rejected Newton step. Returns the
     * frictional residual after it.
     */
    double
    frictionless_fallback_step(double                     mu,
                               const std::vector<Vec3>   &u_star,
                               const std::vector<double> &inv_w,
                               const std::vector<double> &inv_j,
                               double                     dt,
                               double                     tolerance,
                               std::vector<Vec3>         &u,
                               std::vector<Vec3>         &w);

    /// Relative velocity of row @p k's contact for (u, w): with @p affine
    /// its constraint value c and tangential velocity, otherwise the linear
    /// parts only (no gap, no wall surface velocity).
    void
    row_velocity(std::size_t              k,
                 const std::vector<Vec3> &u,
                 const std::vector<Vec3> &w,
                 bool                     affine,
                 double                  &c,
                 Vec3                    &v_t) const;

    /// W_t of row @p k: its tangential Delassus entry.
    double
    tangential_weight(std::size_t                k,
                      const std::vector<double> &inv_w,
                      const std::vector<double> &inv_j) const
    {
      return inv_w[a_[k]] + inv_w[b_[k]] +
             lever_a_[k] * lever_a_[k] * inv_j[a_[k]] +
             lever_b_[k] * lever_b_[k] * inv_j[b_[k]];
    }

    /// Add the impulse (dn e + dt) of row @p k to the velocities (u, w) of
    /// its bodies.
    void
    add_impulse(std::size_t                k,
                double                     dn,
                const Vec3                &dt,
                const std::vector<double> &inv_w,
                const std::vector<double> &inv_j,
                std::vector<Vec3>         &u,
                std::vector<Vec3>         &w) const;

    /// Dual objective 1/2 lambda^T A lambda + b^T lambda, from u.
    double
    dual_objective(const std::vector<Vec3>   &u_star,
                   const std::vector<double> &inv_w,
                   const std::vector<Vec3>   &u) const;

    /// Gauss-Seidel sweeps between two subspace steps.
    static constexpr unsigned int sweeps_per_subspace_step = 3;
    /// Sweeps over the rows with an impulse after each full frictional sweep.
    static constexpr unsigned int active_sweeps = 8;
    /// Frictional Newton step: linear residual over nonlinear residual.
    static constexpr double newton_forcing = 1e-2;
    /// Frictional Newton step: the full step, then halved, at most this
    /// many times in all.
    static constexpr unsigned int newton_attempts = 3;
    /// Bound on the conjugate-gradient iterations of one subspace step.
    static constexpr unsigned int max_cg_iterations = 30;
    /// Stall detection of the frictional sweeps: iterations per window.
    static constexpr unsigned int stall_window = 100;
    /// A window is stalled if its smallest residual is above this fraction
    /// of the previous window's.
    static constexpr double stall_progress = 0.9;
    /// Relaxation after each stalled window: multiplied by this factor ...
    static constexpr double relaxation_factor = 0.8;
    /// ... down to this value.
    static constexpr double minimum_relaxation = 0.5;

    /**
     * Tracks the residuals of the frictional iterations by windows of
     * stall_window and lowers relaxation_ after a window that did not
     * make progress (ConstraintSystem::solve_frictional()).
     */
    struct StallMonitor
    {
      double       previous_minimum;
      double       minimum;
      unsigned int count = 0;
    };

    /// Record @p residual in @p monitor; relax the sweeps if it stalled.
    void
    relax_if_stalled(double residual, StallMonitor &monitor);

    /// Fraction of each exact local update that the frictional sweeps take.
    double relaxation_ = 1.;

    std::vector<std::uint32_t> a_, b_;
    std::vector<Vec3>          e_;
    std::vector<double>        gap_;
    std::vector<char>          glued_;
    std::vector<double>        lambda_;
    std::vector<double>        gamma_;
    std::vector<double>        rhs_;       ///< (D_k - offset_k) / dt
    std::vector<double>        diag_;      ///< A_kk = 1/w_a + 1/w_b
    std::vector<double>        offset_;    ///< contact distance
    std::vector<double>        lever_a_;   ///< centre to contact, first body
    std::vector<double>        lever_b_;   ///< centre to contact, second body
    std::vector<Vec3>          lambda_t_;  ///< tangential impulses
    std::vector<Vec3>          surface_a_; ///< first body's surface velocity
  };
} // namespace Fidus::Contact

#endif
