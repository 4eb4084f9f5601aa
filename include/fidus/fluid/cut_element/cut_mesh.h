#ifndef fidus_fluid_cut_mesh_h
#define fidus_fluid_cut_mesh_h

#include <algorithm>
#include <array>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * The mesh of CutStokesInclusion: the box [0, L_0] x ... (Settings::
   * box_sides; the unit box by default) divided into coarse cells of about
   * unit size (round(L_d) along axis d, so of sides in [0.75, 1.5): cubes
   * when every side is a whole number, otherwise boxes whose sides differ
   * by less than a factor 2),
   * refined in bands around
   * the particle surfaces and in the thin gaps between them, and where
   * each of its cells lies relative to the particles (inside one, cut by
   * one surface, or in the fluid).
   *
   * Along periodic axes a particle near a face also appears shifted by one
   * period: every ball that reaches into the box is listed with the
   * particle it images (its owner). The mesh is made to match cell for
   * cell across each pair of periodic faces, so that periodicity is an
   * identity between the DoFs of matched faces (make_periodicity_
   * constraints()) and the ghost penalties see matched cells as neighbours
   * (periodic_neighbours()). doc/cut_element.md, "Periodic faces".
   */
  template <int dim>
  class CutMesh
  {
  public:
    /// A ball of the mesh: a particle or one of its periodic images.
    struct Ball
    {
      Point<dim>   center;
      double       radius = 0.;
      unsigned int owner  = 0;
    };

    /// Where a cell lies: inside a ball (solid), or the number of surfaces
    /// it meets and the last of those balls.
    struct Placement
    {
      bool         solid = false;
      unsigned int n_cut = 0;
      unsigned int ball  = 0;
    };

    /// How the mesh is refined.
    struct Settings
    {
      /// Global refinement of the box's coarse cells.
      unsigned int global_level = 4;
      /// The box [0, L_0] x ... x [0, L_{dim-1}], every side at least 1
      /// (the shortest side is the length unit); empty: the unit box.
      std::vector<double> box_sides;
      /// Further levels in a band around the particle surfaces.
      unsigned int band_levels = 0;
      /// Width of that band in cells of the level being refined.
      double band_cells = 3.;
      /// Refine a cut cell closer than this many of its sizes to another
      /// particle or to a wall (0: only cells cut by two surfaces, which
      /// must be).
      double gap_cells = 0.;
      /// At most this many levels beyond global_level + band_levels for
      /// the gap refinement.
      unsigned int max_gap_levels = 14;
      /// The periodic axes; the faces of every other axis are walls.
      std::vector<unsigned int> periodic_axes;
    };

    /// A cell on a lower periodic face and its matched cell on the upper
    /// one (same level, same position across the face).
    struct PeriodicPair
    {
      unsigned int axis;
      int          lower_level, lower_index;
      int          upper_level, upper_index;
    };

    /**
     * Build the mesh for the particles at @p centers with @p radii (the
     * centres in the box; along periodic axes any value, taken modulo the
     * period). Throws std::invalid_argument if a cell stays cut by two
     * surfaces after the allowed gap levels.
     */
    CutMesh(const std::vector<Point<dim>> &centers,
            const std::vector<double>     &radii,
            const Settings                &settings);

    /// The triangulation.
    const Triangulation<dim> &
    get_triangulation() const
    {
      return triangulation;
    }

    /// Every ball that reaches into the box.
    const std::vector<Ball> &
    get_balls() const
    {
      return balls;
    }

    /// Where the active cell @p cell lies.
    template <typename CellIterator>
    const Placement &
    placement(const CellIterator &cell) const
    {
      return placements[cell->active_cell_index()];
    }

    /// The matched cells across periodic faces.
    const std::vector<PeriodicPair> &
    periodic_neighbours() const
    {
      return periodic_pairs;
    }

    /**
     * Add u(upper) = u(lower) for every DoF on an upper periodic face
     * that has a partner on the matched lower cell and is not constrained
     * yet. Cells without unknowns (inside a particle) have no partner to
     * give: the DoFs facing them stay free, as at a particle's inner faces.
     * Call after the hanging-node and boundary constraints.
     */
    void
    make_periodicity_constraints(const DoFHandler<dim>     &dof_handler,
                                 AffineConstraints<double> &constraints) const;

    /// Refinement flags set for thin gaps, and for matching periodic faces.
    unsigned int n_gap_refinements = 0, n_periodic_refinements = 0;

    /// The box's side along axis @p d.
    double
    side(const unsigned int d) const
    {
      return sides[d];
    }

    /**
     * A cell's size h in the penalties and inverse estimates of the
     * formulation (Nitsche's term): its shortest side. Every cell is a cube
     * when the box's sides are whole
     * numbers; otherwise it is a box whose sides differ by less than a
     * factor 2, and the shortest side is the one the inverse estimates
     * see.
     */
    template <typename CellIterator>
    static double
    shortest_side(const CellIterator &cell)
    {
      double h = cell->extent_in_direction(0);
      for (unsigned int d = 1; d < dim; ++d)
        h = std::min(h, cell->extent_in_direction(d));
      return h;
    }

    /// A cell's longest side: the reach of the refinement rules (bands,
    /// gaps) in cells, so that a rule gives at least its cells along every
    /// axis.
    template <typename CellIterator>
    static double
    longest_side(const CellIterator &cell)
    {
      double h = cell->extent_in_direction(0);
      for (unsigned int d = 1; d < dim; ++d)
        h = std::max(h, cell->extent_in_direction(d));
      return h;
    }

  private:
    /// The box's sides, and the sides of its coarse cells.
    std::array<double, dim>   sides, coarse;
    Triangulation<dim>        triangulation;
    std::vector<Ball>         balls;
    std::vector<Placement>    placements;
    std::vector<PeriodicPair> periodic_pairs;

    /// Append to balls each particle wrapped into the box along the
    /// periodic axes, and its images within reach of the box.
    void
    add_balls_with_images(const std::vector<Point<dim>> &centers,
                          const std::vector<double>     &radii,
                          const Settings                &s,
                          const std::vector<bool>       &periodic);

    /// Throw std::invalid_argument if two particles touch or overlap.
    void
    check_gaps() const;

    /// Refine the band of cells along the particles' surfaces.
    void
    refine_band(const Settings &s);

    /// Refine the cut cells cut twice or at a thin gap (to another particle
    /// or a wall), within the level limit.
    void
    refine_gaps(const Settings &s, const std::vector<bool> &periodic);

    /// Flag the coarser cell of every unmatched pair across @p axis;
    /// true if any flag was set.
    bool
    flag_periodic_mismatch(const unsigned int axis);

    /// Match the cells of the faces across @p axis (the mesh matches).
    void
    collect_periodic_pairs(const unsigned int axis);
  };
} // namespace Fidus

#endif
