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

    void
    vector_value(const Point<dim> &x, Vector<double> &values) const override;

  private:
    const SolidIndicator<dim>                &solid;
    const std::vector<std::array<double, 3>> &forces;
  };
} // namespace Fidus

#endif
