#include <fidus/fluid/undisturbed/undisturbed_shear_model.h>
#include <fidus/particles/isolated_drag.h>
#include <limits>

namespace Fidus
{
  template <int dim>
  UndisturbedShearModel<dim>::UndisturbedShearModel(
    const Parameters       &parameters,
    const BoxGeometry<dim> &box_geometry)
    : prm(parameters)
    , box(box_geometry)
  {}



  template <int dim>
  typename UndisturbedShearModel<dim>::Statistics
  UndisturbedShearModel<dim>::rigid_velocities(const std::vector<Vec3> &X,
                                               const double             g,
                                               const SolveLabel        &label,
                                               std::vector<Vec3>       &U,
                                               std::vector<Vec3>       &W)
  {
    (void)label;
    for (unsigned int i = 0; i < X.size(); ++i)
      {
        U[i] = {{g * (X[i][1] - box.y_mid), 0., 0.}};
        W[i] = {{0., 0., -0.5 * g}};
      }
    // An external force moves a free-draining particle relative to the
    // flow at F over its isolated drag (6 pi eta a for a sphere, fidus's
    // 4 pi eta for a disc); it exerts no torque.
    if (!prm.particles.external_forces.empty())
      for (unsigned int i = 0; i < X.size(); ++i)
        {
          const double drag =
            isolated_drag(dim, prm.fluid.viscosity, prm.particles.radii[i]);
          for (unsigned int d = 0; d < dim; ++d)
            U[i][d] += prm.particles.external_forces[i][d] / drag;
        }
    return Statistics();
  }



  template <int dim>
  typename UndisturbedShearModel<dim>::Stress
  UndisturbedShearModel<dim>::hydrodynamic_stress(const double g)
  {
    // Free-draining particles carry no stress of their own: the
    // undisturbed shear flow's viscous stress.
    Stress s;
    s.volume = 1.;
    for (unsigned int d = 0; d < dim; ++d)
      s.volume *= box.hi[d] - box.lo[d];
    s.total[0][1]            = prm.fluid.viscosity * g;
    s.mean_strain_rate[0][1] = 0.5 * g;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        s.wall[a][b] = std::numeric_limits<double>::quiet_NaN();
    s.stresslets.assign(prm.n_particles(), dealii::SymmetricTensor<2, 3>());
    return s;
  }



  template <int dim>
  double
  UndisturbedShearModel<dim>::cfl_length() const
  {
    return box.a_min;
  }



  template <int dim>
  bool
  UndisturbedShearModel<dim>::resolves_gap_flow() const
  {
    return false;
  }



  template class UndisturbedShearModel<2>;
  template class UndisturbedShearModel<3>;
} // namespace Fidus
