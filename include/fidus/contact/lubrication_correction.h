#ifndef fidus_contact_lubrication_correction_h
#define fidus_contact_lubrication_correction_h

#include <array>
#include <cstdint>
#include <fidus/contact/contact_types.h>
#include <fidus/contact/pair_search.h>
#include <limits>
#include <vector>

namespace Fidus::Contact
{
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
    /// Gaps below roughness * (smaller radius of the pair; the radius for a
    /// wall) count as that gap: the resistance stops growing there and the
    /// contact model takes over.
    double roughness = 5e-3;
    /// True when the fluid solve carries no hydrodynamic interaction at all
    /// (undisturbed shear): the resolved resistance is then zero instead of
    /// that of the gap h_c.
    bool nothing_resolved = false;
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
    /// the part the fluid solve already carries.
    double r_true     = 0.;
    double r_resolved = 0.;
    double force      = 0.;
  };

  /**
   * Sub-grid lubrication: the squeeze resistance of the gaps the mesh cannot
   * resolve, added to the particle velocities of the fluid solve (the
   * dense-suspension issue; doc/fluid.md, "Lubrication").
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
   * farther than h_c keep u = u*; so does an isolated particle. Only the
   * normal (squeeze) term is corrected: it is the one singular as h^-1
   * (spheres) or h^-3/2 (discs); the tangential terms grow like log(1/h)
   * (spheres) and are left to the mesh.
   *
   * The squeeze resistance of two spheres (or a sphere and a plane, radius
   * infinite) with reduced radius R = a_1 a_2 / (a_1 + a_2) is 6 pi eta R^2
   * / h, of two discs per unit length 3 sqrt(2) pi eta (R / h)^{3/2}
   * (leading order of the Reynolds lubrication equation in the gap).
   */
  class LubricationCorrection
  {
  public:
    explicit LubricationCorrection(const LubricationSettings &settings);

    /// Walls whose squeeze resistance counts (see ContactProjector).
    void
    set_walls(const std::vector<Wall> &walls);

    /// Periodic directions (see PairSearch::set_periodicity()).
    void
    set_periodicity(const std::array<double, 3> &periods);

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
     * Correct the predicted velocities @p u_star of particles at @p positions
     * with @p radii: @p u receives the velocities of the system with the
     * sub-grid squeeze resistance (u = u* where no pair is closer than the
     * range). Only translations change. Throws ContactError if the positions
     * or velocities are not finite.
     *
     * With @p dt > 0 the velocities are meant for an explicit Euler step of
     * that size, and each close pair's normal velocity is then lowered by
     * the gap that the step would open through their relative tangential
     * motion alone, (|r + dt w| - |r| - dt n.w) / dt, so that the gap
     * changes by dt times the lubricated normal speed. Without that, a pair
     * that turns as a doublet ratchets its gap open by |w_t|^2 dt^2 / 2l per
     * step, which the lubrication then keeps from closing (doc/fluid.md).
     */
    LubricationStatistics
    correct(const std::vector<Vec3>   &positions,
            const std::vector<double> &radii,
            const std::vector<Vec3>   &u_star,
            std::vector<Vec3>         &u,
            double                     dt = 0.);

    /// The bonds of the last correction, with their forces.
    const std::vector<LubricationBond> &
    bonds() const
    {
      return bond;
    }

    /// The drag zeta_i used for a particle of radius @p a.
    double
    drag(double a) const;

  private:
    /// y = A x for the corrected system (or its resolved part).
    void
    apply(const std::vector<double> &zeta,
          bool                       resolved,
          const std::vector<double> &x,
          std::vector<double>       &y) const;

    LubricationSettings          settings;
    PairSearch                   search;
    std::vector<Wall>            walls;
    std::vector<LubricationBond> bond;
  };
} // namespace Fidus::Contact

#endif
