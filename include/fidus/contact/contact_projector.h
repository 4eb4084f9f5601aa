#ifndef fidus_contact_contact_projector_h
#define fidus_contact_contact_projector_h

#include <array>
#include <fidus/contact/constraint_system.h>
#include <fidus/contact/contact_error.h>
#include <fidus/contact/contact_types.h>
#include <fidus/contact/glue_state.h>
#include <fidus/contact/pair_search.h>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace Fidus::Contact
{
  /**
   * The contact corrector of numerics section 3: projects the predicted
   * translational velocities u* of the particles onto the admissible set K of
   * the chosen model (none, inelastic, gluey), with walls, and carries the
   * glue state of every pair from one step to the next.
   *
   * Each call of project() does: validate the input; find the pairs (and
   * particle-wall pairs) within the alert distance with a cell list, plus
   * every glued pair whatever its distance (minimum image in the periodic
   * directions, see set_periodicity()); build the linearised rows
   * D + dt G v >= 0 (= 0 if glued); solve the dual problem warm-started from
   * the previous step's multipliers; update the glue gamma <- min(0, gamma -
   * dt lambda) (gluey). The projector never moves the particles.
   */
  class ContactProjector
  {
  public:
    /// Store the settings; throws ContactError if they are inconsistent.
    explicit ContactProjector(const Settings &settings);

    /**
     * Set the walls (faces of the box with zero normal velocity). Each
     * particle-wall pair gets its own glue variable. Throws ContactError for
     * an axis outside the dimension, a side other than +-1 or a wall velocity
     * with a normal component (in- or outflow: not a wall). Changing the
     * walls forgets the glue of particle-wall pairs.
     */
    void
    set_walls(const std::vector<Wall> &walls);

    /**
     * Make direction d periodic with period @p periods[d] > 0 (0: not
     * periodic, the default for every direction), e.g. the `sliding walls'
     * box: periodic in x (and z), walls in y. Every particle-particle pair
     * then uses the minimum-image convention: its separation s_ij is
     * X_j - X_i with a multiple of the period removed in each periodic
     * direction so that |s_ij[d]| <= L_d / 2, its gap is
     * D_ij = |s_ij| - a_i - a_j and its normal e_ij = s_ij / |s_ij|. Positions
     * may thus be given wrapped into the box or not, with the same result;
     * the glue of a pair is still identified by (i, j), so a glued pair that
     * crosses a periodic face stays glued.
     *
     * Throws ContactError for a negative or non-finite period, a period in a
     * direction that does not exist (z in 2D), or a periodic direction that
     * also has a wall (set_walls() checks the same the other way round).
     * Whether the periods are large enough is checked by project(), which
     * knows the radii and the alert distance.
     */
    void
    set_periodicity(const std::array<double, 3> &periods);

    /// The periods set with set_periodicity() (0: not periodic).
    const std::array<double, 3> &
    get_periodicity() const
    {
      return search.get_periodicity();
    }

    /**
     * Weights w_i of the norm |v - u*|_W (default: all 1, the paper's choice).
     * An empty vector restores the default. Weights must be positive.
     */
    void
    set_weights(const std::vector<double> &weights);

    /// A wall's velocity at a point on it, when it varies along the wall.
    using WallVelocity =
      std::function<Vec3(const Wall &wall, const Vec3 &point)>;

    /**
     * The velocity of each wall at each contact point, for friction (a z
     * wall in linear shear moves with the flow at its height; Wall::velocity
     * holds one velocity per wall). Empty: Wall::velocity everywhere. The
     * velocity returned must be tangential to the wall.
     */
    void
    set_wall_velocity(WallVelocity field)
    {
      wall_velocity = std::move(field);
    }

    /**
     * Rotational weights j_i of the norm |v - u*|_W + |omega - omega*|_J,
     * which only friction uses. An empty vector (the default) takes those of
     * a particle whose rotational and translational resistances are an
     * isolated sphere's (8 pi eta a^3 against 6 pi eta a, so j = 4/3 a^2 w
     * in 3D) or disc's (4 pi eta a^2 against 4 pi eta, j = a^2 w in 2D).
     */
    void
    set_rotational_weights(const std::vector<double> &weights);

    /**
     * Project predicted translational velocities onto K (numerics section 3)
     * for one step of size @p dt, then (gluey) update the glue state
     * gamma <- min(0, gamma - dt lambda) with snapping to zero above
     * -glue_snap.
     *
     * @p positions, @p radii and @p predicted have one entry per particle; in
     * 2D the z components are ignored (corrected z = predicted z).
     * @p corrected is resized and overwritten.
     *
     * Throws ContactError on: dt <= 0 or NaN, a non-finite predicted
     * velocity or position (the message names the particle), a radius <= 0,
     * an initial overlap beyond the overlap tolerance (the message names the
     * pair i, j or particle and wall, and the overlap), size mismatch. The
     * overlap check is skipped for model none, where overlaps are expected.
     *
     * With periodic directions (set_periodicity()), also throws if a period
     * L is not larger than 2 (2 a_max + d_a) (a_max the largest radius, d_a
     * the alert distance, also after it has been enlarged): below that, two
     * images of the same pair can both be within the alert distance, and one
     * row per pair (the minimum image) no longer describes K.
     *
     * Non-convergence of the dual solver does not throw: the statistics say
     * converged = false and give the residual; the caller reports it.
     *
     * Alert distance: a pair enters K if its gap is below
     * d_a = max(settings.alert_distance, alert_factor dt max|u*|),
     * alert_factor >= 2. Two particles that both move at most U close their
     * gap by at most 2 dt U in one step, so 2 dt max|u| is enough *for the
     * corrected* velocities u. But the correction can make a particle faster
     * than any predicted one (a particle squeezed between two converging
     * neighbours is ejected at a speed that grows like 1/tan of the contact
     * angle; a glued cluster drags its members), so no fixed multiple of
     * max|u*| is safe in all cases. The default factor 3 covers the common
     * case (chains, clusters averaging velocities never exceed max|u*|, and
     * ejection gains up to 1.5 are covered); the guarantee comes from an a
     * posteriori check: after the solve, if 2 dt max|u| > d_a the search is
     * redone with d_a = alert_factor dt max|u| (warm started) until it
     * holds. Then every pair left out has D > d_a >= dt |u_j - u_i|, so by
     * convexity of the gap it cannot overlap after the step.
     */
    ProjectionStatistics
    project(const std::vector<Vec3>   &positions,
            const std::vector<double> &radii,
            const std::vector<Vec3>   &predicted,
            double                     dt,
            std::vector<Vec3>         &corrected);

    /**
     * The same, with the rows of glued pairs along the line of centres at
     * @p glued_normal_positions instead of @p positions: the middle of the
     * step, estimated by the caller. The equality of a glued row, D + dt
     * e.(u_j - u_i) = 0, then keeps a touching pair's distance exactly when
     * e is the direction at the step's exact middle: with d the separation
     * and w = dt (u_j - u_i), e parallel to d + w/2 gives |d + w| = |d|. With
     * the normals of the start of the step, a glued pair that turns moves
     * along the chord and opens its gap by O(dt^2) per step, which the next
     * step closes again; that is not symmetric in time, and a reversed run
     * does not undo it (doc/results.md, "A time-symmetric scheme"). Rows
     * that are not glued keep the normals of @p positions, which make the
     * linearised gap a lower bound of the true one after the step (no
     * overlap, by convexity).
     */
    ProjectionStatistics
    project(const std::vector<Vec3>   &positions,
            const std::vector<double> &radii,
            const std::vector<Vec3>   &predicted,
            double                     dt,
            std::vector<Vec3>         &corrected,
            const std::vector<Vec3>   &glued_normal_positions);

    /**
     * Project translational and angular velocities: the same projection,
     * and with Settings::friction > 0 the Coulomb friction of every contact
     * (ConstraintSystem::solve_frictional()), which changes the rotations
     * too. @p predicted_rotation holds one angular velocity per particle (z
     * component only in 2D); @p corrected_rotation is resized and
     * overwritten. @p glued_normal_positions as in the other project(), or
     * null for the normals of @p positions.
     */
    ProjectionStatistics
    project(const std::vector<Vec3>   &positions,
            const std::vector<double> &radii,
            const std::vector<Vec3>   &predicted,
            const std::vector<Vec3>   &predicted_rotation,
            double                     dt,
            std::vector<Vec3>         &corrected,
            std::vector<Vec3>         &corrected_rotation,
            const std::vector<Vec3>   *glued_normal_positions = nullptr);

    /// Number of glued pairs (particle-particle and particle-wall).
    unsigned int
    n_glued() const;

    /**
     * The overlap the next projection accepts in its input: the settings'
     * overlap tolerance, or, after a projection that stopped short of its
     * tolerance, twice that projection's residual, so that the next one
     * can push apart what it left instead of stopping the run.
     */
    double
    tolerated_overlap() const;

    /// What tolerated_overlap() carries over from the last projection:
    /// twice its residual if it did not converge, else 0 (kept in
    /// checkpoints, so that a resumed run accepts what a stalled
    /// projection left, as the uninterrupted run does).
    double
    overlap_carried() const
    {
      return carried_overlap;
    }

    /// Continue from a saved overlap_carried() (a resumed run).
    void
    restore_overlap_carried(const double overlap)
    {
      carried_overlap = overlap;
    }

    /// Number of glued contacts that involve each particle (for output).
    std::vector<unsigned int>
    glued_count_per_particle(std::size_t n_particles) const;

    /// Forget the glue state and the warm start.
    void
    reset_glue();

    /// Continue from saved glue entries (a resumed run): the next
    /// projection sees exactly the state glue_state() had when saved.
    void
    restore_glue(std::vector<GlueState::Entry> entries)
    {
      glue.rebuild(std::move(entries));
    }

    /// The glue state after the last projection (pair identity, gamma,
    /// last multiplier).
    const GlueState &
    glue_state() const
    {
      return glue;
    }

    /**
     * The rows of the last projection with their multipliers (bodies
     * 0..N-1 are particles, N + w is wall w), for checks of the KKT
     * conditions and diagnostics.
     */
    const ConstraintSystem &
    constraints() const
    {
      return system;
    }

    /// The settings in use.
    const Settings &
    get_settings() const
    {
      return settings;
    }

    /**
     * Smallest gap D of a configuration: over all particle pairs with
     * gap < @p search_distance (found with the O(N) cell list) and over all
     * particle-wall pairs. Returns +infinity if there are no walls and no
     * pair closer than @p search_distance. A negative value is an overlap.
     * @p dimension is 2 or 3 (2D ignores z).
     *
     * @p periods as in set_periodicity() (default: nothing periodic): pair
     * gaps are then minimum-image gaps, the smallest over the images of the
     * pair, whether the positions are wrapped into the box or not. Throws
     * ContactError if a period is not larger than 4 a_max (then two images
     * of a pair can overlap at once, so one gap per pair does not describe
     * the configuration), or for the errors of set_periodicity(). A large
     * @p search_distance needs no larger period: the minimum image is the
     * closest image whatever the distance.
     */
    static double
    minimum_gap(const std::vector<Vec3>     &positions,
                const std::vector<double>   &radii,
                const std::vector<Wall>     &walls,
                unsigned int                 dimension,
                double                       search_distance,
                const std::array<double, 3> &periods = {{0., 0., 0.}});

  private:
    void
    validate(const std::vector<Vec3>   &positions,
             const std::vector<double> &radii,
             const std::vector<Vec3>   &predicted,
             double                     dt) const;

    /**
     * Throw if a period is too small for the largest radius @p a_max and the
     * alert distance @p d_a (see project()).
     */
    void
    check_periods(double a_max, double d_a) const;

    /// All project(): glued rows take their normals at
    /// @p glued_normal_positions unless it is null; rotations are projected
    /// when @p rotation holds the predicted and corrected ones.
    ProjectionStatistics
    project_with(const std::vector<Vec3>   &positions,
                 const std::vector<double> &radii,
                 const std::vector<Vec3>   &predicted,
                 double                     dt,
                 std::vector<Vec3>         &corrected,
                 const std::vector<Vec3>   *glued_normal_positions,
                 const std::pair<const std::vector<Vec3> *, std::vector<Vec3> *>
                   &rotation);

    /// The angular velocities and rotational weights of the bodies.
    void
    set_up_rotations(const std::vector<double> &radii,
                     const std::vector<Vec3>   &rotation);

    /// The velocity of @p wall at the contact of the particle centred at
    /// @p centre, beyond Wall::velocity (zero without friction).
    Vec3
    wall_surface_velocity(const Wall &wall, const Vec3 &centre) const;

    /// Solve the assembled rows (with friction if it is on).
    ConstraintSystem::Result
    solve_rows(double dt);

    /// Build the rows for alert distance @p d_a (glued rows' normals at
    /// @p glued_normal_positions unless null); returns the smallest gap.
    double
    assemble(const std::vector<Vec3>   &positions,
             const std::vector<double> &radii,
             double                     d_a,
             const std::vector<Vec3>   *glued_normal_positions);

    Settings settings;
    /// Twice the residual of the last projection if it did not converge,
    /// else 0 (tolerated_overlap()).
    double              carried_overlap = 0.;
    std::vector<Wall>   walls;
    std::vector<double> weights;
    std::vector<double> rotational_weights;
    WallVelocity        wall_velocity;

    PairSearch       search;
    GlueState        glue;
    ConstraintSystem system;

    /// Work arrays kept between calls.
    std::vector<PairSearch::Pair> pairs;
    std::vector<char>             glue_seen;
    std::vector<Vec3>             u_star, u, w_star, w;
    std::vector<double>           inv_w, inv_j;
  };
} // namespace Fidus::Contact

#endif
