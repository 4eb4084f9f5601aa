#ifndef fidus_particles_isolated_drag_h
#define fidus_particles_isolated_drag_h

#include <cmath>

namespace Fidus
{
  /**
   * The drag of an isolated particle of radius @p a in a fluid of
   * viscosity @p viscosity, the force per unit velocity: 6 pi eta a for a
   * sphere (Stokes). A disc (a cylinder per unit length) has no
   * free-space drag (Stokes' paradox); 4 pi eta is its size at a few
   * radii from walls, and what fidus takes in 2D.
   */
  inline double
  isolated_drag(const unsigned int dim, const double viscosity, const double a)
  {
    return dim == 3 ? 6. * M_PI * viscosity * a : 4. * M_PI * viscosity;
  }
} // namespace Fidus

#endif
