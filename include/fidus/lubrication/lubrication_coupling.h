#ifndef fidus_lubrication_lubrication_coupling_h
#define fidus_lubrication_lubrication_coupling_h

#include <fidus/lubrication/lubrication_correction.h>
#include <vector>

namespace Fidus::Contact
{
  /**
   * The sub-grid lubrication solved with the flow of a fluid model whose
   * particles carry no rigid velocity unknowns (the fictitious domain,
   * `Fluid/Lubrication coupling = with the flow`).
   *
   * The bonds of LubricationCorrection::find_bonds() exert the loads
   * L(x) = -D x + w on the particles at generalised velocities x (six per
   * particle: U, omega), with D the resistance between the true gaps and
   * the resolved ones (symmetric, positive semi-definite) and w the
   * forcing of the walls' motion. The fluid solve with those loads as body
   * forces in the particles gives rigid velocities u(L(x)); the coupled
   * velocities are its fixed point x = u(L(x)). The fluid model iterates
   *
   *   x <- x + P (u(L(x)) - x),   P = (Z + D)^-1 Z,
   *
   * with Z = zeta + R_res standing for the inverse of the fluid solve's
   * mobility: the isolated drags and the resistance the mesh itself shows
   * each bond (LubricationCorrection::resolved_loads(), the same model of
   * the fluid as the correction after the solve). The error after a step
   * is (Z + D)^-1 (I - Z M) D e for the fluid's mobility M: zero outside
   * the bonds, and small on them as far as Z models M. With the isolated
   * drags alone, Z M was near 0 on the relative motion of close pairs (the
   * mesh resists it far more) and the iteration hardly moved. The fluid
   * model accelerates it with Anderson mixing.
   *
   * Everything here is small (six unknowns per particle) and replicated on
   * every rank, like the correction.
   */
  class LubricationCoupling
  {
  public:
    /// The bonds are those of @p correction's last find_bonds() for
    /// particles of radii @p radii; both must outlive this object.
    LubricationCoupling(const LubricationCorrection &correction,
                        const std::vector<double>   &radii);

    /// The loads of all bonds at the generalised velocities @p x: the force
    /// and the torque on each particle (walls moving as set on the
    /// correction).
    void
    loads(const std::vector<double> &x,
          std::vector<Vec3>         &force,
          std::vector<Vec3>         &torque) const;

    /**
     * The step P r = (Z + D)^-1 Z @p r of the iteration for the
     * residual @p r = u(L(x)) - x, by Jacobi-preconditioned conjugate
     * gradients to the correction's tolerance; returns the iterations, or
     * throws ContactError if they do not converge.
     */
    unsigned int
    step(const std::vector<double> &r, std::vector<double> &s) const;

  private:
    /// y = (Z + D) x.
    void
    apply(const std::vector<double> &x, std::vector<double> &y) const;

    const LubricationCorrection &correction;
    /// The translational and rotational drag of each particle.
    std::vector<double> zeta, zeta_rot;
    /// The diagonal of Z + D, for Jacobi.
    std::vector<double> diagonal;
  };
} // namespace Fidus::Contact

#endif
