#ifndef fidus_particles_particle_force_density_h
#define fidus_particles_particle_force_density_h

#include <array>
#include <deal.II/base/function.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <vector>

namespace Fidus
{
  /**
   * The body force that carries external forces on the particles into the
   * Stokes problem (Particles/External force): inside particle i (or one of
   * its periodic images) the force density F_i / |B_i|, with |B_i| the
   * exact volume of its solid ball (area in 2D: F_i is then per unit
   * length), and zero in the fluid. The rigidity multiplier makes the solid
   * move as one body, so the particle feels the net force F_i up to the
   * cut-cell quadrature of its volume; the fluid carries it to the walls.
   *
   * With torques, particle i also carries the density T_i x r / J_i (r
   * from the centre of the ball, J_i = int |r|^2 (2D: pi a^4 / 2) or
   * 2/3 int |r|^2 (3D: 8 pi a^5 / 15) over the ball), whose moment about
   * the centre is T_i and whose net force is zero (2D: T_i = (0, 0, tau)).
   *
   * Components 0..dim-1 are the force density, component dim (the
   * pressure's) is zero, as StokesSolver::solve() expects of a body force.
   */
  template <int dim>
  class ParticleForceDensity : public Function<dim>
  {
  public:
    /// @p solid must outlive this object and be set up for the current
    /// positions; @p forces has one force per particle.
    ParticleForceDensity(const SolidIndicator<dim>                &solid,
                         const std::vector<std::array<double, 3>> &forces);

    /// Forces and torques, one of each per particle (both must outlive this
    /// object; their values may change between solves).
    ParticleForceDensity(const SolidIndicator<dim>                &solid,
                         const std::vector<std::array<double, 3>> &forces,
                         const std::vector<std::array<double, 3>> &torques);

    void
    vector_value(const Point<dim> &x, Vector<double> &values) const override;

  private:
    const SolidIndicator<dim>                &solid;
    const std::vector<std::array<double, 3>> &forces;
    /// Null: no torques.
    const std::vector<std::array<double, 3>> *torques = nullptr;
  };
} // namespace Fidus

#endif
