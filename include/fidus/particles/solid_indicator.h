#ifndef fidus_particles_solid_indicator_h
#define fidus_particles_solid_indicator_h

#include <array>
#include <deal.II/base/point.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The characteristic function I of the solid region (numerics section 1)
   * and the geometric queries the mesh and the fluid need: which particle
   * contains a point, which particles may meet a ball (a cell), the distance
   * to the nearest particle surface.
   *
   * Particles are sorted into a uniform bin grid whose bins are about one
   * particle diameter wide, so that every query costs O(1) for a suspension
   * of equal spheres instead of O(N): assembly asks it at every quadrature
   * point of every cell.
   */
  template <int dim>
  class SolidIndicator
  {
  public:
    /// Build the bins for the given particles; the bin grid covers the box.
    void
    reinit(const std::vector<std::array<double, 3>> &positions,
           const std::vector<double>                &radii,
           const Point<dim>                         &lower_left,
           const Point<dim>                         &upper_right);

    /// Number of particles.
    unsigned int
    n_particles() const
    {
      return centers.size();
    }

    /// Centre of particle @p i.
    const Point<dim> &
    center(const unsigned int i) const
    {
      return centers[i];
    }

    /// Radius of particle @p i.
    double
    radius(const unsigned int i) const
    {
      return radii[i];
    }

    /**
     * Append to @p out (after clearing it) the particles whose ball meets the
     * ball of centre @p x and radius @p r: candidates for a cell of that
     * bounding ball.
     */
    void
    candidates(const Point<dim>          &x,
               const double               r,
               std::vector<unsigned int> &out) const;

    /// Index of the particle that contains @p x among @p candidates, or -1.
    int
    particle_containing(const Point<dim>                &x,
                        const std::vector<unsigned int> &candidates) const;

    /// Index of the particle that contains @p x, or -1.
    int
    particle_containing(const Point<dim> &x) const;

    /**
     * Unsigned distance from @p x to the nearest particle surface, searched
     * among the particles that meet the ball (x, @p search_radius); returns
     * @p search_radius if none does.
     */
    double
    distance_to_surfaces(const Point<dim> &x, const double search_radius) const;

  private:
    unsigned int
    bin_index(const std::array<int, dim> &b) const;

    std::vector<Point<dim>>                centers;
    std::vector<double>                    radii;
    Point<dim>                             origin;
    double                                 bin_size = 1.;
    std::array<int, dim>                   n_bins;
    std::vector<std::vector<unsigned int>> bins;
    mutable std::vector<unsigned int>      scratch;
  };
} // namespace Fidus

#endif
