#ifndef fidus_fluid_boundary_velocity_h
#define fidus_fluid_boundary_velocity_h

#include <deal.II/base/function.h>
#include <fidus/core/parameters.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * Velocity imposed on the faces of the box (dim + 1 components, the last
   * one, pressure, is zero), for 'linear shear', 'sliding walls' and
   * 'cavity' (numerics section 1). The shear rate value is set per time step
   * with set_shear_rate().
   *
   * All three are built on the undisturbed shear u = g (y - y_mid) e_x:
   * linear shear imposes it everywhere; sliding walls and cavity impose it on
   * the faces y = y_min, y_max (where it is -/+ g H / 2) and zero on the
   * remaining faces of the cavity (periodic faces carry no condition).
   */
  template <int dim>
  class BoundaryVelocity : public Function<dim>
  {
  public:
    /// @p y_min, @p y_max: the extent of the box in y.
    BoundaryVelocity(const BoundaryCondition bc,
                     const double            y_min,
                     const double            y_max);

    /// Set the shear rate used by value().
    void
    set_shear_rate(const double g)
    {
      shear_rate = g;
    }

    double
    value(const Point<dim> &p, const unsigned int component) const override;

  private:
    const BoundaryCondition bc;
    const double            y_min, y_max;
    double                  shear_rate = 0.;
  };
} // namespace Fidus

#endif
