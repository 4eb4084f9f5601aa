#ifndef fidus_rheology_suspension_stress_h
#define fidus_rheology_suspension_stress_h

#include <deal.II/base/symmetric_tensor.h>
#include <string>
#include <vector>

namespace Fidus
{
  /**
   * The rheology columns of statistics.csv for one step (doc/rheology.md),
   * from the hydrodynamic stress of the box (HydrodynamicStress) and the
   * contact stress of the projection (contact_stress()). Shear in the
   * x-y plane, velocity along x, gradient along y.
   *
   * - shear_stress: Sigma_xy of the whole suspension (hydrodynamic +
   *   contact); relative_viscosity = Sigma_xy / (eta_f gamma_dot), NaN when
   *   gamma_dot = 0;
   * - normal_stress_difference_1 = Sigma_xx - Sigma_yy,
   *   normal_stress_difference_2 = Sigma_yy - Sigma_zz (2D: plane strain);
   * - particle_pressure: -tr(Sigma_p) / 3 of the particle stress (the
   *   particles' stresslets and the contacts), -(xx + yy) / 2 in 2D;
   * - contact_relative_viscosity: the contact part of relative_viscosity;
   * - wall_shear_stress: the hydrodynamic Sigma_xy from the traction on the
   *   walls (NaN without walls at y = const), to compare with
   *   hydrodynamic_shear_stress, the same from the volume average;
   * - contact_particle_pressure: the contact part of particle_pressure;
   * - lubrication_relative_viscosity, lubrication_particle_pressure: the
   *   part of the sub-grid lubrication forces (zero without
   *   Fluid/Lubrication correction), included in the totals above.
   */
  struct SuspensionStress
  {
    double shear_stress                   = 0.;
    double relative_viscosity             = 0.;
    double normal_stress_difference_1     = 0.;
    double normal_stress_difference_2     = 0.;
    double particle_pressure              = 0.;
    double contact_relative_viscosity     = 0.;
    double wall_shear_stress              = 0.;
    double hydrodynamic_shear_stress      = 0.;
    double contact_particle_pressure      = 0.;
    double lubrication_relative_viscosity = 0.;
    double lubrication_particle_pressure  = 0.;

    /**
     * Combine the box's hydrodynamic stress @p hydrodynamic (3 x 3, 2D in
     * plane strain), its particle part @p particle, the walls' shear stress
     * @p wall_xy and the contact stress @p contact, for fluid viscosity
     * @p eta_f and shear rate @p shear_rate in dimension @p dim, and the
     * stress of the lubrication forces @p lubrication.
     */
    static SuspensionStress
    combine(const dealii::SymmetricTensor<2, 3> &hydrodynamic,
            const dealii::SymmetricTensor<2, 3> &particle,
            double                               wall_xy,
            const dealii::SymmetricTensor<2, 3> &contact,
            double                               eta_f,
            double                               shear_rate,
            unsigned int                         dim,
            const dealii::SymmetricTensor<2, 3> &lubrication =
              dealii::SymmetricTensor<2, 3>());

    /// Column names, in the order of values().
    static std::vector<std::string>
    column_names();

    /// The values, in the order of column_names().
    std::vector<double>
    values() const;
  };
} // namespace Fidus

#endif
