#include <cmath>
#include <deal.II/base/numbers.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/fictitious_domain/particle_force_density.h>
#include <fidus/particles/particle_measure.h>

namespace Fidus
{
  template <int dim>
  ParticleForceDensity<dim>::ParticleForceDensity(
    const SolidIndicator<dim>                &solid,
    const std::vector<std::array<double, 3>> &forces)
    : Function<dim>(dim + 1)
    , solid(solid)
    , forces(forces)
  {}



  template <int dim>
  ParticleForceDensity<dim>::ParticleForceDensity(
    const SolidIndicator<dim>                &solid,
    const std::vector<std::array<double, 3>> &forces,
    const std::vector<std::array<double, 3>> &torques)
    : Function<dim>(dim + 1)
    , solid(solid)
    , forces(forces)
    , torques(&torques)
  {}



  template <int dim>
  void
  ParticleForceDensity<dim>::vector_value(const Point<dim> &x,
                                          Vector<double>   &values) const
  {
    values             = 0.;
    int          entry = -1;
    const double phi   = solid.fraction(x, entry);
    if (phi == 0.)
      return;
    const unsigned int i      = solid.owner(entry);
    const double       a      = solid.radius(entry);
    const double       volume = particle_measure(dim, a);
    for (unsigned int d = 0; d < dim; ++d)
      values[d] = phi * forces[i][d] / volume;
    if (!torques)
      return;
    // T x r / J: a rigid rotation's density, whose moment is T.
    const std::array<double, 3> &T = (*torques)[i];
    const Point<dim>             c = solid.center(entry);
    std::array<double, 3>        r{{0., 0., 0.}};
    for (unsigned int d = 0; d < dim; ++d)
      r[d] = x[d] - c[d];
    const double J = dim == 3 ? 8. / 15. * numbers::PI * std::pow(a, 5) :
                                0.5 * numbers::PI * std::pow(a, 4);
    const std::array<double, 3> t{{T[1] * r[2] - T[2] * r[1],
                                   T[2] * r[0] - T[0] * r[2],
                                   T[0] * r[1] - T[1] * r[0]}};
    for (unsigned int d = 0; d < dim; ++d)
      values[d] += phi * t[d] / J;
  }



  template class ParticleForceDensity<2>;
  template class ParticleForceDensity<3>;
} // namespace Fidus
