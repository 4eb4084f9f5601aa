#ifndef fidus_contact_lubrication_correction_h
#define fidus_contact_lubrication_correction_h

#include <array>
#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <fidus/contact/pair_search.h>
#include <functional>
#include <limits>
#include <vector>

namespace Fidus::Contact
{
  /// Which gaps' resistance slows a lubrication bond over a time step.
  enum class GapInTime
  {
    /// the gap at the start of the step (explicit)
    start,
    /// the mean over the gaps the step passes through for a closing gap,
    /// the start's for an opening one
    closing_mean,
    /// the mean over the gaps the step passes through, closing or opening
    step_mean
  };

  /// Settings of the sub-grid lubrication correction.
  struct LubricationSettings
  {
    unsigned int dimension = 2;
    /// Fluid viscosity eta_f.
    double viscosity = 1.;
    /// Gap h_c (length) below which the mesh no longer resolves the squeeze
    /// flow: pairs closer than this are corrected, and the fluid solve is
    /// taken to carry the squeeze resistance of a gap h_c for them.
    double range = 0.;
    /// The same for particle-wall gaps; < 0: the same as range. A wall is
    /// a mesh face, so the mesh resolves the squeeze against it further
    /// down than between two cut particle surfaces (doc/lubrication.md).
    double wall_range = -1.;
    /// Gap h_f (length) whose squeeze resistance the fluid solve shows when
    /// the ambient flow, not a force, closes a pair's gap; < 0: the same as
    /// range. The mesh resists a flow-driven approach less than a
    /// force-driven one (doc/history/lubrication_sheared_pair.md, "Two spheres
    /// held in shear"), so the two parts of u* are corrected from different
    /// gaps: the part driven by the external forces (set_external_forces())
    /// from range, the rest from flow_range.
    double flow_range = -1.;
    /// Gap h_o (length) at which the flow's resolved gap meets the true
    /// one: below it the fluid solve is taken to show, for a flow-driven
    /// approach, the squeeze resistance of the gap h_f + (1 - h_f / h_o) h,
    /// which rises linearly from flow_range at contact to h_o. The mesh
    /// loses the flow-driven squeeze gradually from about two thirds of a
    /// cell, not at once at h_f (doc/theory/lubrication.md). <= flow_range:
    /// the step max(h, h_f).
    double flow_edge = -1.;
    /// Gap (length) down to which the mesh carries the tangential
    /// resistance of two particles sliding past each other; < 0: the same
    /// as range. Pair bonds reach out to the largest of range, flow_range,
    /// flow_edge
    /// and this one.
    double tangential_range = -1.;
    /// Gap (length) down to which the mesh carries the tangential
    /// resistance of a particle sliding along a wall; < 0: the same as
    /// wall_range. The mesh resolves sliding less far down than the squeeze
    /// (doc/lubrication_2d.md, "Squeeze of a disc against a wall"), so wall
    /// bonds reach out to the larger of the two, and a bond between them
    /// corrects only the tangential terms.
    double tangential_wall_range = -1.;
    /// > 0: the fluid solve resolves every gap down to this fraction of
    /// the smaller radius of a pair (the radius for a wall) and sees the
    /// narrower gaps at that width (the cut finite element with its
    /// minimum gap). Every range above is then this gap, bond by bond:
    /// what the fluid carries is the resistance of a pair at that gap, and
    /// the correction adds the rest. 0: the ranges above, in lengths.
    double resolved_gap_fraction = 0.;
    /// Gaps below roughness * (smaller radius of the pair; the radius for a
    /// wall) count as that gap: the resistance stops growing there and the
    /// contact model takes over.
    double roughness = 5e-3;
    /// True when the fluid solve carries no hydrodynamic interaction at all
    /// (undisturbed shear): the resolved resistance is then zero instead of
    /// that of the gap h_c.
    bool nothing_resolved = false;
    /// Also correct the tangential terms: the resistance to the sliding of
    /// the two surfaces past each other and to their relative rotation,
    /// which couples translations and rotations (h^-1/2 for discs, log(1/h)
    /// for spheres). false: the normal squeeze only.
    bool tangential = false;
    /// With a step dt > 0 in correct(): the gaps whose squeeze resistance
    /// slows each bond over the step (see StepMeanResistance).
    GapInTime gap_in_time = GapInTime::start;
    /// Resistance of one particle to translation, force per velocity; 0:
    /// the isolated Stokes drag, 6 pi eta a in 3D and 4 pi eta per unit
    /// length in 2D.
    double drag = 0.;
    /// Conjugate-gradient stop, relative to the right-hand side.
    double       tolerance      = 1e-12;
    unsigned int max_iterations = 10000;
  };

  /// What one correction did.
  struct LubricationStatistics
  {
    /// Particle-particle and particle-wall pairs closer than the range.
    unsigned int n_pairs      = 0;
    unsigned int n_wall_pairs = 0;
    /// Pairs whose gap is below the roughness (resistance capped there).
    unsigned int n_rough    = 0;
    unsigned int iterations = 0;
    /// Final CG residual relative to the right-hand side.
    double residual  = 0.;
    bool   converged = true;
  };

  /**
   * One lubrication bond of the last correction: particle i with particle j
   * or with wall `wall` (then j is `no_particle`). n is the unit vector from
   * i to j (minimum image), or the wall's normal pointing away from the
   * particle (towards the wall), `length` the centre distance (for a wall,
   * the centre-to-wall distance), and `force` the normal force that the
   * correction adds on j (on i it is the opposite): positive pushes the
   * two apart.
   */
  struct LubricationBond
  {
    static constexpr std::uint32_t no_particle =
      std::numeric_limits<std::uint32_t>::max();
    std::uint32_t i      = 0;
    std::uint32_t j      = no_particle;
    unsigned int  wall   = 0;
    Vec3          n      = {{0., 0., 0.}};
    double        length = 0.;
    double        gap    = 0.;
    /// Squeeze resistance of the true gap (capped by the roughness) and of
    /// the part the fluid solve already carries: in its response to the
    /// flow (r_resolved) and to the external forces (r_resolved_force). Each
    /// is that of the larger of the gap and its range.
    double r_true           = 0.;
    double r_resolved       = 0.;
    double r_resolved_force = 0.;
    double force            = 0.;
    /// Radii of the two surfaces; a_j = 0 for a wall.
    double a_i = 0.;
    double a_j = 0.;
    /// Tangential resistance coefficient c of the true gap and of the range
    /// (see tangential_resistance()); zero without tangential terms.
    double t_true     = 0.;
    double t_resolved = 0.;
    /// Tangential velocity of the wall (sliding walls); zero for a pair.
    Vec3 wall_velocity = {{0., 0., 0.}};
    /// The tangential force the correction adds on j (on i it is the
    /// opposite; for a wall, on the wall), and the torques it adds on i and
    /// j about their centres.
    Vec3 tangential_force = {{0., 0., 0.}};
    Vec3 torque_i         = {{0., 0., 0.}};
    Vec3 torque_j         = {{0., 0., 0.}};
  };

  /**
   * Sub-grid lubrication: the squeeze resistance of the gaps the mesh cannot
   * resolve, added to the particle velocities of the fluid solve (the
   * dense-suspension issue; doc/lubrication.md, "Lubrication").
   *
   * The fluid solve gives force-free velocities u* of a system whose
   * resistance is modelled, per particle, as the isolated drag zeta_i and,
   * per close pair, the squeeze resistance R(h_c) of a gap at the cut-off
   * h_c: the mesh cannot resolve more. The true system has R(max(h, delta))
   * instead. With the same driving forces on both, the corrected velocities
   * u solve
   *
   *   zeta_i u_i + sum_k R_k n_k n_k.(u_i - u_j)
   *     = zeta_i u*_i + sum_k Rres_k n_k n_k.(u*_i - u*_j),
   *
   * a symmetric positive definite system in the velocities (implicit: the
   * resistance of a closing gap acts on the velocity that closes it). Pairs
   * farther than h_c keep u = u*; so does an isolated particle.
   *
   * The mesh shows a pair a different resolved resistance when the ambient
   * flow closes its gap (that of a gap h_f, LubricationSettings::flow_range)
   * than when a force pushes it (h_c). With external forces F, the part of
   * u* they drive is modelled as the solution u*_F of the resolved system
   * with R(h_c) and F on the right, and the right-hand side becomes
   *
   *   zeta_i u*_i + sum_k [R(h_f) n_k n_k.(u*_i - u*_j)
   *                        + (R(h_c) - R(h_f)) n_k n_k.(u*_F,i - u*_F,j)],
   *
   * which gives the true resistance's response to both the flow and the
   * forces when the mesh behaves as modelled.
   *
   * With LubricationSettings::tangential the same is done for the
   * tangential terms, with the angular velocities w among the unknowns
   * (rotational drag 8 pi eta a^3 in 3D, 4 pi eta a^2 per unit length in
   * 2D). From the Reynolds equation of the gap between two surfaces of
   * radii a_i, a_j (n from i to j, surface velocities at the gap
   * s_i = U_i + w_i x a_i n and s_j = U_j - w_j x a_j n), the tangential
   * force on j and the shear forces on the two surfaces are
   *
   *   F_j = -c (dU - k d S),  shear on j: -c (dU + k S), on i: c (dU - k S),
   *
   * with dU = P (s_j - s_i), S = P (s_i + s_j - 2 R (U_i / a_i + U_j / a_j))
   * (P the projection on the tangent plane; the last term is the motion of
   * the gap's profile), d = (a_i - a_j) / (a_i + a_j), k = 1 in 2D and
   * 3/5 in 3D, and the torques those shear forces exert at the gap points.
   * c = pi eta sqrt(2 R / h) per unit length for discs, 2 pi eta R
   * log(L / h) for spheres (L = max(R, h_c): only the difference between
   * two gaps is fixed by lubrication theory). This resistance is symmetric,
   * positive semi-definite and zero for a rigid motion of the pair; it
   * reproduces the known sphere-wall log coefficients 8/15, 2/15 and 2/5
   * and the cylinder-wall 2 sqrt(2) pi eta (a/h)^1/2 (doc/lubrication.md,
   * "Lubrication").
   *
   * The squeeze resistance of two spheres (or a sphere and a plane, radius
   * infinite) with reduced radius R = a_1 a_2 / (a_1 + a_2) is 6 pi eta R^2
   * / h + 6 pi eta a_1 b (1 + 7b + b^2) / (5 (1 + b)^3) log(1/xi), b = a_2 /
   * a_1, xi = 2h / (a_1 + a_2) (h / a_1 for a plane, where the factor is
   * 1/5; Jeffrey & Onishi 1984), of two discs per unit length
   * 3 sqrt(2) pi eta (R / h)^{3/2} (leading order of the Reynolds
   * lubrication equation in the gap).
   */
  class LubricationCorrection
  {
  public:
    explicit LubricationCorrection(const LubricationSettings &settings);

    /// Walls whose squeeze resistance counts (see ContactProjector).
    void
    set_walls(const std::vector<Wall> &walls);

    /**
     * How fast the walls move where a particle faces them: @p velocity
     * (wall, point on the wall) replaces Wall::velocity for the next
     * correct() calls (its normal component is dropped). Sheared boxes
     * need it, since their walls move with the shear rate of the step, and
     * the faces of a linear-shear box move differently from point to point.
     */
    void
    set_wall_velocity(
      std::function<Vec3(const Wall &wall, const Vec3 &point)> velocity);

    /// Periodic directions (see PairSearch::set_periodicity()).
    void
    set_periodicity(const std::array<double, 3> &periods);

    /// The external force on each particle that drives the fluid solve
    /// (per unit length in 2D); empty (the default): none.
    void
    set_external_forces(const std::vector<Vec3> &forces);

    /// The settings, e.g. the range h_c.
    const LubricationSettings &
    get_settings() const
    {
      return settings;
    }

    /**
     * Normal squeeze resistance (force per relative normal velocity) of a gap
     * @p gap between particles of radii @p a1 and @p a2; @p a2 = 0 stands
     * for a plane wall. Per unit length in 2D.
     */
    static double
    squeeze_resistance(unsigned int dimension,
                       double       viscosity,
                       double       a1,
                       double       a2,
                       double       gap);

    /**
     * Tangential resistance coefficient c (see the class documentation) of
     * a gap @p gap between radii @p a1 and @p a2 (0: a wall), for a
     * correction of range @p range.
     */
    static double
    tangential_resistance(unsigned int dimension,
                          double       viscosity,
                          double       a1,
                          double       a2,
                          double       gap,
                          double       range);

    /**
     * Loads of the tangential terms of bond @p b with coefficient @p c for
     * the velocities @p v = (U_i, w_i, U_j, w_j): the forces and torques the
     * gap exerts, (F_i, T_i, F_j, T_j); a wall bond uses the first six
     * entries and its wall moves with b.wall_velocity. b.n, b.a_i and b.a_j
     * must be set.
     */
    static std::array<double, 12>
    tangential_loads(const LubricationBond        &b,
                     double                        c,
                     unsigned int                  dimension,
                     const std::array<double, 12> &v);

    /**
     * The normal speed at which the translational velocities @p u (of all
     * particles) close the gap of bond @p b: n.(u_i - u_j), or n.u_i for a
     * wall, which does not move normally.
     */
    static double
    approach_speed(const LubricationBond &b, const std::vector<Vec3> &u);

    /**
     * The length of bond @p b (centre distance, or a centre's distance from
     * the wall) after the explicit Euler step X += dt u that moves the
     * particles: |l n + dt (u_j - u_i)| for a pair, l - dt n.u_i for a wall.
     */
    static double
    length_after_step(const LubricationBond   &b,
                      const std::vector<Vec3> &u,
                      double                   dt);

    /**
     * Correct the predicted translational and angular velocities @p u_star
     * and @p w_star (angular velocity about z in 2D, in component 2): @p u
     * and @p w receive the corrected ones. Without tangential terms w =
     * w_star and u is what the other overload gives.
     */
    LubricationStatistics
    correct(const std::vector<Vec3>   &positions,
            const std::vector<double> &radii,
            const std::vector<Vec3>   &u_star,
            const std::vector<Vec3>   &w_star,
            std::vector<Vec3>         &u,
            std::vector<Vec3>         &w,
            double                     dt = 0.);

    /**
     * Correct the predicted velocities @p u_star of particles at @p positions
     * with @p radii: @p u receives the velocities of the system with the
     * sub-grid squeeze resistance (u = u* where no pair is closer than the
     * range). Only translations change; with tangential terms the particles
     * are taken not to turn (w* = 0). Throws ContactError if the positions
     * or velocities are not finite.
     *
     * With @p dt > 0 the velocities are meant for an explicit Euler step of
     * that size, and each close pair's normal velocity is then lowered by
     * the gap that the step would open through their relative tangential
     * motion alone, (|r + dt w| - |r| - dt n.w) / dt, so that the gap
     * changes by dt times the lubricated normal speed. Without that, a pair
     * that turns as a doublet ratchets its gap open by |w_t|^2 dt^2 / 2l per
     * step, which the lubrication then keeps from closing (doc/lubrication.md).
     */
    LubricationStatistics
    correct(const std::vector<Vec3>   &positions,
            const std::vector<double> &radii,
            const std::vector<Vec3>   &u_star,
            std::vector<Vec3>         &u,
            double                     dt = 0.);

    /**
     * For a fluid model that solves the sub-grid resistance together with
     * the flow (the cut finite element, LubricationSettings::
     * resolved_gap_fraction): the bonds of the particles at @p positions
     * with @p radii, their resistances filled and their forces zero. The
     * model adds subgrid_loads() of each to its own system; measure() then
     * records the forces of the velocities it solved.
     *
     * @p fluid_radii, if not empty, are the radii the fluid was solved
     * with, smaller than @p radii where the model shrank a particle to
     * leave the resolved gap: the fluid then carries each gap at its own
     * widened width, and every gap the shrinking widened gets a bond (the
     * resistance between its true and its fluid width), not only those
     * below the resolved gap fraction.
     */
    const std::vector<LubricationBond> &
    find_bonds(const std::vector<Vec3>   &positions,
               const std::vector<double> &radii,
               const std::vector<double> &fluid_radii = {});

    /**
     * The loads (F_i, T_i, F_j, T_j) that bond @p b adds at the generalised
     * velocities @p v = (U_i, w_i, U_j, w_j): the resistance between the
     * true gap and the resolved one (the normal squeeze, and the
     * tangential terms with LubricationSettings::tangential). They resist
     * the relative motion, are linear in @p v and, when @p wall_motion,
     * include the motion of a wall bond's wall.
     */
    std::array<double, 12>
    subgrid_loads(const LubricationBond        &b,
                  const std::array<double, 12> &v,
                  bool                          wall_motion) const;

    /**
     * The loads (F_i, T_i, F_j, T_j) of the resistance that the fluid solve
     * itself shows bond @p b in its response to a force (the normal squeeze
     * of r_resolved_force, and the tangential terms of t_resolved with
     * LubricationSettings::tangential) at the generalised velocities @p v,
     * walls at rest: linear in @p v. The model of the fluid's resistance
     * in Contact::LubricationCoupling.
     */
    std::array<double, 12>
    resolved_loads(const LubricationBond        &b,
                   const std::array<double, 12> &v) const;
    /**
     * Record on the bonds of the last find_bonds() the forces of the
     * velocities @p u and angular velocities @p w that the fluid model
     * solved with them (for the stress and the statistics); the
     * velocities are not changed.
     */
    LubricationStatistics
    measure(const std::vector<Vec3> &u, const std::vector<Vec3> &w);

    /// The bonds of the last correction, with their forces.
    const std::vector<LubricationBond> &
    bonds() const
    {
      return bond;
    }

    /// The drag zeta_i used for a particle of radius @p a.
    double
    drag(double a) const;

    /// The rotational drag used for a particle of radius @p a: 8 pi eta a^3
    /// (3D), 4 pi eta a^2 (2D), or drag(a) times 4 a^2 / 3 (3D) and a^2
    /// (2D) when LubricationSettings::drag is set.
    double
    rotational_drag(double a) const;

  private:
    /// The statistics of the last find_bonds().
    LubricationStatistics found;

    /// Which resistance of the bonds a system uses.
    enum class Resistance
    {
      /// the true gap's
      true_gap,
      /// what the fluid solve carries in its response to the flow
      resolved,
      /// what it carries in its response to the external forces
      resolved_force
    };

    /// The normal squeeze resistance and the tangential coefficient of
    /// bond @p b in the system @p resistance.
    static std::array<double, 2>
    resistances(const LubricationBond &b, Resistance resistance);

    /// y = A x for the corrected system (or its resolved parts); x and y
    /// hold 6 values per particle, the velocity and the angular velocity.
    void
    apply(const std::vector<double> &zeta,
          const std::vector<double> &zeta_rot,
          Resistance                 resistance,
          const std::vector<double> &x,
          std::vector<double>       &y) const;

    /// Solve A x = @p rhs by Jacobi-preconditioned conjugate gradients, from
    /// the initial @p x; records iterations and residual in @p stat.
    void
    solve(const std::vector<double> &zeta,
          const std::vector<double> &zeta_rot,
          Resistance                 resistance,
          const std::vector<double> &rhs,
          std::vector<double>       &x,
          LubricationStatistics     &stat) const;

    /// The solution of the corrected system with its drags, the predicted
    /// velocities and the external forces' part (defined in the .cc file).
    struct CorrectedSystem;

    /// Sets the true and resolved resistances of bond @p b (gap floored at
    /// the roughness of @p a_small) and says whether the bond is kept: the
    /// same test for particle pairs and walls, hence one function. The
    /// flow's resolved gap rises from @p flow_range to @p flow_edge (a
    /// step if flow_edge <= flow_range; LubricationSettings::flow_edge).
    /// The resolved resistances are those of surfaces of radii
    /// @p resolved_radii (the fluid's, if it saw them shrunk; negative:
    /// the bond's own).
    bool
    fill_resistances(LubricationBond             &b,
                     double                       a_small,
                     double                       range,
                     double                       flow_range,
                     double                       flow_edge,
                     double                       tangential_range,
                     LubricationStatistics       &stat,
                     const std::array<double, 2> &resolved_radii = {
                       {-1., -1.}}) const;

    /// Appends to the bonds those of the particle pairs, then of the walls,
    /// within range of the squeeze; counts them in @p stat. @p fluid_radii
    /// as in find_bonds().
    void
    collect_bonds(const std::vector<Vec3>   &positions,
                  const std::vector<double> &radii,
                  LubricationStatistics     &stat,
                  const std::vector<double> &fluid_radii = {});

    /// Solves for the part of u* that the external forces drive and takes
    /// the difference of the two resolved resistances on it off @p rhs;
    /// returns that part, or nothing if both responses are the same.
    std::vector<double>
    subtract_force_response(const std::vector<double> &zeta,
                            const std::vector<double> &zeta_rot,
                            std::vector<double>       &rhs,
                            LubricationStatistics     &stat) const;

    /// Assembles and solves the corrected system A_true u = b for the
    /// current bonds.
    CorrectedSystem
    solve_corrected_system(const std::vector<double> &radii,
                           const std::vector<Vec3>   &u_star,
                           const std::vector<Vec3>   &w_star,
                           LubricationStatistics     &stat) const;

    /// Stores in each bond the loads it adds to the corrected velocities.
    void
    compute_bond_loads(const CorrectedSystem &s);

    /// LubricationSettings::gap_in_time other than start: re-solves the
    /// corrected system of @p s with each bond's squeeze resistance
    /// averaged over the gaps from its start to where the step of size
    /// @p dt takes it, until those end gaps agree to a thousandth of the
    /// start gaps (at most 30 solves).
    void
    average_over_step(CorrectedSystem       &s,
                      double                 dt,
                      LubricationStatistics &stat);

    /// Adds to @p u the Euler step's tangential opening of each pair (a time
    /// integration matter, hence after the bond loads).
    void
    add_step_opening(const std::vector<double> &zeta,
                     double                     dt,
                     std::vector<Vec3>         &u) const;

    LubricationSettings settings;
    PairSearch          search;
    std::vector<Wall>   walls;
    /// See set_wall_velocity(); empty: Wall::velocity.
    std::function<Vec3(const Wall &, const Vec3 &)> wall_velocity_at;
    std::vector<LubricationBond>                    bond;
    std::vector<Vec3>                               external_force;
  };
} // namespace Fidus::Contact

#endif
