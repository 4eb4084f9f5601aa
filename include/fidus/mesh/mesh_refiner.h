#ifndef fidus_mesh_mesh_refiner_h
#define fidus_mesh_mesh_refiner_h

#include <deal.II/distributed/tria.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>

namespace Fidus
{
  using namespace dealii;

  /**
   * Geometric adaptive refinement around particles (numerics section 4).
   *
   * A cell is refined (up to the maximum level) when its distance to a
   * particle surface is below 'band' cells of its own size, or when it lies
   * in the gap of a close pair (closer than the gap distance to both
   * surfaces of a pair whose gap is below that distance); every other cell is
   * coarsened towards the minimum level. Since each pass moves a cell by one
   * level, passes are repeated until the mesh no longer changes. The result
   * is a graded mesh: finest at the surfaces, `band` cells per level outward.
   */
  template <int dim>
  class MeshRefiner
  {
  public:
    /// Refinement settings.
    struct Settings
    {
      unsigned int minimum_level = 3;
      unsigned int maximum_level = 8;
      double       band          = 1.;
      double       gap_distance  = 0.5; ///< relative to the smaller radius
    };

    explicit MeshRefiner(const Settings &settings)
      : settings(settings)
    {}

    /**
     * Adapt @p triangulation to the particles of @p solid. Returns the number
     * of passes that changed the mesh (0: the mesh was already adapted).
     */
    unsigned int
    adapt(parallel::distributed::Triangulation<dim> &triangulation,
          const SolidIndicator<dim>                 &solid) const;

  private:
    /// The level a cell of centre @p x and size @p h should have at least.
    bool
    wants_refinement(const Point<dim>          &x,
                     const double               h,
                     const SolidIndicator<dim> &solid) const;

    const Settings settings;
  };
} // namespace Fidus

#endif
