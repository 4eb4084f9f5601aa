// Adaptive refinement around particles (numerics section 4), 2D and 3D: the
// mesh is finest at the particle surfaces (every cell that the surface
// crosses is on the maximum level), coarse far away (the cell diameter
// grows with the distance d to the nearest surface: no cell away from the
// surface is finer than d / (4 (band + 1/2)), the band rule with a factor 2
// of slack for the 2:1 balance), and a close pair gets its gap refined to
// the maximum level.

#include "../fidus_test.h"

#include <deal.II/distributed/tria.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/mesh/box_mesh.h>
#include <fidus/mesh/mesh_refiner.h>
#include <map>

using namespace dealii;
using namespace FidusTest;

template <int dim>
void
check(const std::vector<std::array<double, 3>> &positions,
      const std::string                        &name)
{
  parallel::distributed::Triangulation<dim> tria(
    MPI_COMM_WORLD,
    typename Triangulation<dim>::MeshSmoothing(
      Triangulation<dim>::smoothing_on_refinement |
      Triangulation<dim>::smoothing_on_coarsening));
  Point<dim> lo, hi;
  for (unsigned int d = 0; d < dim; ++d)
    hi[d] = 1.;
  const unsigned int min_level = 2, max_level = dim == 2 ? 7 : 5;
  Fidus::create_box_mesh(tria, lo, hi, {}, min_level);
  Fidus::SolidIndicator<dim> solid;
  const std::vector<double>  radii(positions.size(), 0.1);
  solid.reinit(positions, radii, lo, hi);
  typename Fidus::MeshRefiner<dim>::Settings settings;
  settings.minimum_level = min_level;
  settings.maximum_level = max_level;
  settings.band          = 2.;
  Fidus::MeshRefiner<dim>(settings).adapt(tria, solid);

  unsigned int surface_cells_not_finest = 0, far_cells_not_coarsest = 0;
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        const double d = solid.distance_to_surfaces(cell->center(), 1.);
        if (d < 0.5 * cell->diameter() && int(cell->level()) != int(max_level))
          ++surface_cells_not_finest;
        if (d > 0.5 * cell->diameter() && cell->level() > min_level &&
            cell->diameter() < d / (4. * (settings.band + 0.5)))
          ++far_cells_not_coarsest;
      }
  surface_cells_not_finest =
    Utilities::MPI::sum(surface_cells_not_finest, MPI_COMM_WORLD);
  far_cells_not_coarsest =
    Utilities::MPI::sum(far_cells_not_coarsest, MPI_COMM_WORLD);
  check_range(name + ": cells crossed by a surface not on the finest level",
              surface_cells_not_finest,
              0,
              0);
  check_range(name + ": cells finer than the grading allows",
              far_cells_not_coarsest,
              0,
              0);

  if (positions.size() == 2)
    {
      // The midpoint of the gap lies in a finest cell.
      Point<dim> mid;
      for (unsigned int d = 0; d < dim; ++d)
        mid[d] = 0.5 * (positions[0][d] + positions[1][d]);
      unsigned int found = 0;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->point_inside(mid))
          found = cell->level() == max_level ? 1 : 2;
      found = Utilities::MPI::max(found, MPI_COMM_WORLD);
      check_range(name + ": gap midpoint on the finest level (1 = yes)",
                  found,
                  1,
                  1);
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>({{{0.5, 0.5, 0.}}}, "2D one particle");
  check<2>({{{0.39, 0.5, 0.}}, {{0.61, 0.5, 0.}}}, "2D close pair");
  check<3>({{{0.5, 0.5, 0.5}}}, "3D one particle");
  return exit_code();
}
