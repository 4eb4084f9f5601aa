#ifndef fidus_fluid_undisturbed_undisturbed_shear_model_h
#define fidus_fluid_undisturbed_undisturbed_shear_model_h

#include <fidus/core/parameters.h>
#include <fidus/fluid/fluid_model.h>
#include <fidus/simulation/box_geometry.h>

namespace Fidus
{
  /**
   * `Fluid/Model = undisturbed shear`: free-draining particles, which
   * neither disturb the flow nor feel each other through it. Each moves
   * with the undisturbed shear flow at its centre, g (y - y_mid) e_x, and
   * turns with its vorticity, -g/2 about z; an external force F adds
   * F over the isolated drag (isolated_drag()). No mesh and no solve: the
   * model of the contact tests and of scenes where only the contact model
   * matters. The stress is the undisturbed flow's viscous stress; the
   * particles carry none of their own.
   */
  template <int dim>
  class UndisturbedShearModel : public FluidModel<dim>
  {
  public:
    using typename FluidModel<dim>::Vec3;
    using typename FluidModel<dim>::Statistics;
    using typename FluidModel<dim>::SolveLabel;
    using typename FluidModel<dim>::Stress;

    UndisturbedShearModel(const Parameters &prm, const BoxGeometry<dim> &box);

    Statistics
    rigid_velocities(const std::vector<Vec3> &X,
                     double                   shear_rate,
                     const SolveLabel        &label,
                     std::vector<Vec3>       &U,
                     std::vector<Vec3>       &W) override;

    Stress
    hydrodynamic_stress(double shear_rate) override;

    double
    cfl_length() const override;

    bool
    resolves_gap_flow() const override;

  private:
    const Parameters       &prm;
    const BoxGeometry<dim> &box;
  };
} // namespace Fidus

#endif
