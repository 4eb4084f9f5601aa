#include <cmath>
#include <deal.II/base/mpi.h>
#include <fidus/mesh/mesh_refiner.h>

namespace Fidus
{
  template <int dim>
  bool
  MeshRefiner<dim>::wants_refinement(const Point<dim>          &x,
                                     const double               h,
                                     const SolidIndicator<dim> &solid) const
  {
    // h is the cell diameter; the cell centre is within h/2 of every point
    // of the cell, so the band is measured from the nearest cell point.
    const double reach = settings.band * h + 0.5 * h;
    if (solid.distance_to_surfaces(x, reach) < reach)
      return true;

    // Gap rule: near both surfaces of a close pair. The candidates are
    // entries of the indicator, periodic images included, so a pair across
    // a periodic face is measured at its minimum-image distance.
    static thread_local std::vector<unsigned int> cands;
    solid.candidates(x,
                     solid.max_radius() * settings.gap_distance + 0.5 * h,
                     cands);
    for (unsigned int a = 0; a < cands.size(); ++a)
      for (unsigned int b = a + 1; b < cands.size(); ++b)
        {
          const unsigned int i = cands[a], j = cands[b];
          const double       limit =
            settings.gap_distance * std::min(solid.radius(i), solid.radius(j));
          const double gap = solid.center(i).distance(solid.center(j)) -
                             solid.radius(i) - solid.radius(j);
          if (gap > limit)
            continue;
          const double di =
            std::abs(x.distance(solid.center(i)) - solid.radius(i));
          const double dj =
            std::abs(x.distance(solid.center(j)) - solid.radius(j));
          if (di < limit + 0.5 * h && dj < limit + 0.5 * h)
            return true;
        }
    return false;
  }



  template <int dim>
  unsigned int
  MeshRefiner<dim>::adapt(
    parallel::distributed::Triangulation<dim> &triangulation,
    const SolidIndicator<dim>                 &solid) const
  {
    unsigned int       changed_passes = 0;
    const unsigned int max_passes =
      settings.maximum_level - settings.minimum_level + 2;
    for (unsigned int pass = 0; pass < max_passes; ++pass)
      {
        unsigned int n_flagged = 0;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const unsigned int level = cell->level();
              const bool         refine =
                wants_refinement(cell->center(), cell->diameter(), solid);
              if (refine && level < settings.maximum_level)
                {
                  cell->set_refine_flag();
                  ++n_flagged;
                }
              else if (level > settings.maximum_level)
                {
                  cell->set_coarsen_flag();
                  ++n_flagged;
                }
              else if (!refine && level > settings.minimum_level)
                {
                  // Coarsen only if the parent would not want refinement
                  // itself, so that cells do not flip back and forth.
                  if (!wants_refinement(cell->parent()->center(),
                                        cell->parent()->diameter(),
                                        solid))
                    {
                      cell->set_coarsen_flag();
                      ++n_flagged;
                    }
                }
            }
        n_flagged =
          Utilities::MPI::sum(n_flagged, triangulation.get_communicator());
        if (n_flagged == 0)
          break;
        const unsigned int n_before = triangulation.n_global_active_cells();
        triangulation.prepare_coarsening_and_refinement();
        triangulation.execute_coarsening_and_refinement();
        // Count the pass as a change even if the number of cells stayed the
        // same: refinements and coarsenings may balance, and the DoFs must
        // then be distributed anew.
        ++changed_passes;
        if (triangulation.n_global_active_cells() == n_before)
          break;
      }
    return changed_passes;
  }

  template class MeshRefiner<2>;
  template class MeshRefiner<3>;
} // namespace Fidus
