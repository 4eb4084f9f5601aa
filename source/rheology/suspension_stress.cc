#include <cmath>
#include <fidus/rheology/suspension_stress.h>
#include <limits>

namespace Fidus
{
  namespace
  {
    /// Minus the mean of the normal stresses that the dimension has.
    double
    pressure_of(const dealii::SymmetricTensor<2, 3> &s, const unsigned int dim)
    {
      double trace = 0.;
      for (unsigned int d = 0; d < dim; ++d)
        trace += s[d][d];
      return -trace / dim;
    }
  } // namespace



  SuspensionStress
  SuspensionStress::combine(const dealii::SymmetricTensor<2, 3> &hydrodynamic,
                            const dealii::SymmetricTensor<2, 3> &particle,
                            const double                         wall_xy,
                            const dealii::SymmetricTensor<2, 3> &contact,
                            const double                         eta_f,
                            const double                         shear_rate,
                            const unsigned int                   dim,
                            const dealii::SymmetricTensor<2, 3> &lubrication)
  {
    const double nan   = std::numeric_limits<double>::quiet_NaN();
    const auto   total = hydrodynamic + contact + lubrication;
    // Plane strain in 2D: every part comes with its zz entry
    // (with_plane_strain_zz()).
    const double scale = shear_rate != 0. ? 1. / (eta_f * shear_rate) : nan;

    SuspensionStress s;
    s.shear_stress               = total[0][1];
    s.relative_viscosity         = total[0][1] * scale;
    s.normal_stress_difference_1 = total[0][0] - total[1][1];
    s.normal_stress_difference_2 = total[1][1] - total[2][2];
    s.particle_pressure = pressure_of(particle + contact + lubrication, dim);
    s.contact_relative_viscosity     = contact[0][1] * scale;
    s.wall_shear_stress              = wall_xy;
    s.hydrodynamic_shear_stress      = hydrodynamic[0][1];
    s.contact_particle_pressure      = pressure_of(contact, dim);
    s.lubrication_relative_viscosity = lubrication[0][1] * scale;
    s.lubrication_particle_pressure  = pressure_of(lubrication, dim);
    return s;
  }



  std::vector<std::string>
  SuspensionStress::column_names()
  {
    return {"shear_stress",
            "relative_viscosity",
            "normal_stress_difference_1",
            "normal_stress_difference_2",
            "particle_pressure",
            "contact_relative_viscosity",
            "wall_shear_stress",
            "hydrodynamic_shear_stress",
            "contact_particle_pressure",
            "lubrication_relative_viscosity",
            "lubrication_particle_pressure"};
  }



  std::vector<double>
  SuspensionStress::values() const
  {
    return {shear_stress,
            relative_viscosity,
            normal_stress_difference_1,
            normal_stress_difference_2,
            particle_pressure,
            contact_relative_viscosity,
            wall_shear_stress,
            hydrodynamic_shear_stress,
            contact_particle_pressure,
            lubrication_relative_viscosity,
            lubrication_particle_pressure};
  }
} // namespace Fidus
