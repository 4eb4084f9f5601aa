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
   *
   * In a periodic direction, a particle that crosses the face of the box
   * also has an image on the other side, so that the solid is seen from
   * both sides of the face. The queries work on entries: entries
   * 0..n_particles()-1 are the particles themselves, further entries are
   * images, owner() maps an entry to its particle.
   */
  template <int dim>
  class SolidIndicator
  {
  public:
    /**
     * Build the bins for the given particles; the bin grid covers the box.
     * Directions with @p periodic true get images of the particles that
     * cross a face or come within @p halo of it (positions must lie in the
     * box in those directions). The halo is the reach of the queries made
     * near a face: with it, a point near a periodic face sees the particles
     * near the opposite face at their minimum-image positions, so that the
     * refinement band and the gap rule continue across the face.
     */
    void
    reinit(const std::vector<std::array<double, 3>> &positions,
           const std::vector<double>                &radii,
           const Point<dim>                         &lower_left,
           const Point<dim>                         &upper_right,
           const std::array<bool, dim>              &periodic = {},
           const double                              halo     = 0.);

    /**
     * Width w of the layer across each particle surface over which the
     * solid fraction() falls from 1 to 0 (Fluid/Solid smoothing). With w = 0
     * (the default) the solid is sharp: fraction() is 1 inside and 0
     * outside. With w > 0 it falls linearly with the distance to the
     * surface, so that what the fluid and the rigid projection see of a
     * particle changes continuously as it moves across the mesh instead of
     * jumping whenever a quadrature point crosses its surface. Queries then
     * reach w/2 beyond each surface. Takes effect at the next reinit().
     */
    void
    set_smoothing_width(const double w)
    {
      smoothing = w;
    }

    /// Largest radius of all particles (0 if there are none).
    double
    max_radius() const
    {
      return largest_radius;
    }

    unsigned int
    n_particles() const
    {
      return n_real;
    }

    /// Number of entries: particles and their periodic images.
    unsigned int
    n_entries() const
    {
      return centers.size();
    }

    /// The particle of entry @p k (k itself unless it is an image).
    unsigned int
    owner(const unsigned int k) const
    {
      return k < n_real ? k : image_owner[k - n_real];
    }

    /// Centre of entry @p i (a particle or an image).
    const Point<dim> &
    center(const unsigned int i) const
    {
      return centers[i];
    }

    /// Radius of entry @p i.
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

    /// Entry (see owner()) that contains @p x among @p candidates, or -1.
    int
    particle_containing(const Point<dim>                &x,
                        const std::vector<unsigned int> &candidates) const;

    /**
     * Solid fraction at @p x among @p candidates, in [0, 1]: with a sharp
     * solid 1 inside a particle and 0 outside, otherwise the linear ramp
     * 1/2 - (|x - X| - a) / w of the nearest surface (see
     * set_smoothing_width()). @p entry is set to the entry (see owner())
     * that gives the largest fraction, or -1 where it is 0.
     */
    double
    fraction(const Point<dim>                &x,
             const std::vector<unsigned int> &candidates,
             int                             &entry) const;

    /// Solid fraction at @p x (see the other overload), searching all bins.
    double
    fraction(const Point<dim> &x, int &entry) const;

    /// Entry (see owner()) that contains @p x, or -1.
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
    double largest_radius = 0.;
    double smoothing      = 0.;
    unsigned int
    bin_index(const std::array<int, dim> &b) const;

    unsigned int                           n_real = 0;
    std::vector<unsigned int>              image_owner;
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
