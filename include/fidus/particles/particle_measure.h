#ifndef fidus_particles_particle_measure_h
#define fidus_particles_particle_measure_h

namespace Fidus
{
  /**
   * The area (2D, a disc) or volume (3D, a sphere) of a particle of radius
   * @p a: what volume fractions and force densities divide by.
   */
  inline double
  particle_measure(const unsigned int dim, const double a)
  {
    constexpr double pi = 3.14159265358979323846;
    return dim == 2 ? pi * a * a : 4. / 3. * pi * a * a * a;
  }
} // namespace Fidus

#endif
