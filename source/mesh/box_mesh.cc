#include <algorithm>
#include <cmath>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <fidus/mesh/box_mesh.h>

namespace Fidus
{
  template <int dim>
  void
  create_box_mesh(parallel::distributed::Triangulation<dim> &triangulation,
                  const Point<dim>                          &lower_left,
                  const Point<dim>                          &upper_right,
                  const std::vector<unsigned int> &periodic_directions,
                  const unsigned int               global_refinements)
  {
    double smallest = upper_right[0] - lower_left[0];
    for (unsigned int d = 1; d < dim; ++d)
      smallest = std::min(smallest, upper_right[d] - lower_left[d]);
    std::vector<unsigned int> repetitions(dim);
    for (unsigned int d = 0; d < dim; ++d)
      repetitions[d] =
        std::max(1u,
                 static_cast<unsigned int>(
                   std::round((upper_right[d] - lower_left[d]) / smallest)));
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              repetitions,
                                              lower_left,
                                              upper_right,
                                              true);

    if (!periodic_directions.empty())
      {
        std::vector<GridTools::PeriodicFacePair<
          typename parallel::distributed::Triangulation<dim>::cell_iterator>>
          pairs;
        for (const unsigned int d : periodic_directions)
          GridTools::collect_periodic_faces(triangulation,
                                            2 * d,
                                            2 * d + 1,
                                            d,
                                            pairs);
        triangulation.add_periodicity(pairs);
      }
    triangulation.refine_global(global_refinements);
  }

  template void
  create_box_mesh(parallel::distributed::Triangulation<2> &,
                  const Point<2> &,
                  const Point<2> &,
                  const std::vector<unsigned int> &,
                  const unsigned int);
  template void
  create_box_mesh(parallel::distributed::Triangulation<3> &,
                  const Point<3> &,
                  const Point<3> &,
                  const std::vector<unsigned int> &,
                  const unsigned int);
} // namespace Fidus
