#include <cmath>
#include <fidus/fluid/boundary_velocity.h>

namespace Fidus
{
  template <int dim>
  BoundaryVelocity<dim>::BoundaryVelocity(const BoundaryCondition bc,
                                          const double            y_min,
                                          const double            y_max)
    : Function<dim>(dim + 1)
    , bc(bc)
    , y_min(y_min)
    , y_max(y_max)
  {}



  template <int dim>
  double
  BoundaryVelocity<dim>::value(const Point<dim>  &p,
                               const unsigned int component) const
  {
    if (component != 0)
      return 0.;
    const double u = shear_rate * (p[1] - 0.5 * (y_min + y_max));
    if (bc == BoundaryCondition::linear_shear ||
        bc == BoundaryCondition::sliding_walls)
      return u;
    // Cavity: only the two y walls move; the tolerance decides which face a
    // DoF on a box edge belongs to (to the moving wall).
    const double tol = 1e-10 * (y_max - y_min);
    if (std::abs(p[1] - y_min) < tol || std::abs(p[1] - y_max) < tol)
      return u;
    return 0.;
  }

  template class BoundaryVelocity<2>;
  template class BoundaryVelocity<3>;
} // namespace Fidus
