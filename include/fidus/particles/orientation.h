#ifndef fidus_particles_orientation_h
#define fidus_particles_orientation_h

#include <array>
#include <cmath>

namespace Fidus
{
  /**
   * Turn the unit quaternion @p q of a sphere's orientation by the angular
   * velocity @p w over @p dt: q <- q + dt/2 (0, w) q, renormalised (an
   * explicit step, exact to O(dt^2) per step; the normalisation keeps it a
   * rotation).
   */
  inline void
  turn_orientation(std::array<double, 4>       &q,
                   const std::array<double, 3> &w,
                   const double                 dt)
  {
    const double                wx = w[0], wy = w[1], wz = w[2];
    const std::array<double, 4> dq   = {{-wx * q[1] - wy * q[2] - wz * q[3],
                                         wx * q[0] + wy * q[3] - wz * q[2],
                                         -wx * q[3] + wy * q[0] + wz * q[1],
                                         wx * q[2] - wy * q[1] + wz * q[0]}};
    double                      norm = 0;
    for (unsigned int k = 0; k < 4; ++k)
      {
        q[k] += 0.5 * dt * dq[k];
        norm += q[k] * q[k];
      }
    for (unsigned int k = 0; k < 4; ++k)
      q[k] /= std::sqrt(norm);
  }
} // namespace Fidus

#endif
