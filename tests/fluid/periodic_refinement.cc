// Refinement across a periodic face ('sliding walls'): a pair whose gap
// spans the face x = 0 / x = 1 gets the gap rule at its minimum-image
// distance, and the band around a particle near the face continues on the
// other side. Both need the solid indicator's periodic images within the
// reach of the refinement queries (the halo); with halo 0 (only particles
// that cross the face get images) the point in the gap is not refined,
// which this test also checks so that it can fail. Run on 1, 2 and 3
// ranks: the adaptive mesh has hanging nodes on the periodic faces, a known
// source of constraints that differ between ranks, so each mesh's
// hanging-node and periodicity constraints (those of StokesSolver, Q2-Q1)
// are checked with AffineConstraints::is_consistent_in_parallel, also for a
// particle that straddles the face.

#include "../fidus_test.h"

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <fidus/fluid/fictitious_domain/solid_indicator.h>
#include <fidus/fluid/fictitious_domain/stokes_solver.h>
#include <fidus/mesh/box_mesh.h>
#include <fidus/mesh/mesh_refiner.h>

using namespace dealii;
using namespace FidusTest;

namespace
{
  constexpr unsigned int min_level = 3, max_level = 8;

  /// Level of the cell that contains @p p (-1 if none on any rank).
  int
  level_at(const parallel::distributed::Triangulation<2> &tria,
           const Point<2>                                &p)
  {
    int level = -1;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned() && cell->point_inside(p))
        level = cell->level();
    return Utilities::MPI::max(level, MPI_COMM_WORLD);
  }

  /// Whether the hanging-node and periodicity constraints of the Stokes
  /// DoFs on @p tria (x periodic, imposed velocity on y = 0 and y = 1) are
  /// the same on every rank that sees a constrained DoF.
  bool
  constraints_consistent(parallel::distributed::Triangulation<2> &tria)
  {
    Fidus::StokesSolver<2> solver(tria, Fidus::StokesSolver<2>::Settings());
    solver.setup_dofs({0}, {2, 3});
    const auto &dof_handler = solver.get_dof_handler();
    IndexSet    active;
    DoFTools::extract_locally_active_dofs(dof_handler, active);
    return solver.get_conforming_constraints().is_consistent_in_parallel(
      Utilities::MPI::all_gather(MPI_COMM_WORLD,
                                 dof_handler.locally_owned_dofs()),
      active,
      MPI_COMM_WORLD);
  }

  /// Adapt a periodic (in x) unit box to @p positions, radius 0.1, with the
  /// given image halo; return the levels at the points @p probes and, if
  /// @p consistent is given, whether the constraints are consistent.
  std::vector<int>
  levels(const std::vector<std::array<double, 3>> &positions,
         const double                              halo,
         const std::vector<Point<2>>              &probes,
         bool                                     *consistent = nullptr)
  {
    parallel::distributed::Triangulation<2> tria(
      MPI_COMM_WORLD,
      Triangulation<2>::MeshSmoothing(
        Triangulation<2>::smoothing_on_refinement |
        Triangulation<2>::smoothing_on_coarsening));
    const Point<2> lo(0., 0.), hi(1., 1.);
    Fidus::create_box_mesh(tria, lo, hi, {0}, min_level);
    Fidus::SolidIndicator<2>  solid;
    const std::vector<double> radii(positions.size(), 0.1);
    solid.reinit(positions, radii, lo, hi, {{true, false}}, halo);
    Fidus::MeshRefiner<2>::Settings settings;
    settings.minimum_level = min_level;
    settings.maximum_level = max_level;
    settings.band          = 1.;
    settings.gap_distance  = 0.5;
    Fidus::MeshRefiner<2>(settings).adapt(tria, solid);
    std::vector<int> result;
    for (const auto &p : probes)
      result.push_back(level_at(tria, p));
    if (consistent)
      *consistent = constraints_consistent(tria);
    return result;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // The reach of the refinement queries on the coarsest cells, as
  // BoxGeometry computes it: max((band + 1/2) h, gap a + h/2), h the
  // diameter of a level-3 cell.
  const double h    = std::sqrt(2.) / 8.;
  const double halo = std::max(1.5 * h, 0.5 * 0.1 + 0.5 * h);

  // Surfaces 0.022 from the face on both sides: gap 0.044 < 0.5 a across
  // it. The band (1.5 cell diameters) brings the face cells to level 7 only
  // (a level-7 cell there is 0.018 from the nearer surface, beyond its
  // reach 0.0166); the gap rule brings them to level 8.
  const std::vector<std::array<double, 3>> pair       = {{{0.122, 0.50, 0.}},
                                                         {{0.878, 0.51, 0.}}};
  const std::vector<Point<2>>              gap_points = {Point<2>(0.001, 0.505),
                                                         Point<2>(0.999, 0.505)};
  bool                                     consistent = false;
  const auto with_halo = levels(pair, halo, gap_points, &consistent);
  check_range("pair across the face: constraints consistent on all ranks "
              "(1 = yes)",
              consistent ? 1 : 0,
              1,
              1);
  check_range("pair across the face: gap at x = 0 on the finest level",
              with_halo[0],
              max_level,
              max_level);
  check_range("pair across the face: gap at x = 1 on the finest level",
              with_halo[1],
              max_level,
              max_level);
  const auto without = levels(pair, 0., gap_points);
  check_range("without the halo the gap at x = 0 is coarser (old behaviour)",
              without[0],
              min_level,
              max_level - 1);

  // A particle whose surface is 0.003 from the face x = 1 (it does not
  // cross it): the band continues at x = 0, where the point 0.004 from the
  // face is 0.007 from the image's surface, within the band.
  const std::vector<std::array<double, 3>> near = {{{0.897, 0.5, 0.}}};
  const auto band = levels(near, halo, {Point<2>(0.004, 0.5)});
  check_range("band continues across the face: level at x = 0.004",
              band[0],
              max_level,
              max_level);

  // A particle that straddles the face (centre 0.02 from x = 0, radius
  // 0.1): its surface crosses the face near y = 0.598, and the cells there
  // are on the finest level on both sides, with hanging nodes on the face.
  const std::vector<std::array<double, 3>> straddling = {{{0.02, 0.5, 0.}}};
  const auto                               across     = levels(straddling,
                             halo,
                             {Point<2>(0.001, 0.5978), Point<2>(0.999, 0.5978)},
                             &consistent);
  check_range("straddling particle: surface cell at x = 0.001 on the finest "
              "level",
              across[0],
              max_level,
              max_level);
  check_range("straddling particle: surface cell at x = 0.999 on the finest "
              "level",
              across[1],
              max_level,
              max_level);
  check_range("straddling particle: constraints consistent on all ranks "
              "(1 = yes)",
              consistent ? 1 : 0,
              1,
              1);
  return exit_code();
}
