#ifndef fidus_mesh_box_mesh_h
#define fidus_mesh_box_mesh_h

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * Build the coarse box mesh: cells that are near-cubes with the side of
   * the smallest box extent, boundary ids 2k (lower) and 2k+1 (upper) on the
   * faces normal to axis k, and periodicity along @p periodic_directions
   * (which must be set before any refinement on a p4est mesh). Then refine
   * globally @p global_refinements times.
   */
  template <int dim>
  void
  create_box_mesh(parallel::distributed::Triangulation<dim> &triangulation,
                  const Point<dim>                          &lower_left,
                  const Point<dim>                          &upper_right,
                  const std::vector<unsigned int> &periodic_directions,
                  const unsigned int               global_refinements);
} // namespace Fidus

#endif
