#include <algorithm>
#include <array>
#include <cmath>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_generator.h>
#include <fidus/fluid/cut_element/cut_mesh.h>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

namespace Fidus
{
  namespace
  {
    enum class Location
    {
      fluid,
      cut,
      solid
    };

    /// Where an axis-parallel cell lies relative to a ball: the nearest
    /// and farthest points of a box from a point are found coordinate-wise.
    template <typename CellIterator, int dim>
    Location
    locate(const CellIterator &cell, const Point<dim> &c, const double a)
    {
      const Point<dim> lo = cell->vertex(0);
      const Point<dim> hi =
        cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1);
      double near2 = 0., far2 = 0.;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double n = std::max({lo[d] - c[d], 0., c[d] - hi[d]});
          const double f =
            std::max(std::abs(lo[d] - c[d]), std::abs(hi[d] - c[d]));
          near2 += n * n;
          far2 += f * f;
        }
      if (near2 >= a * a)
        return Location::fluid;
      if (far2 <= a * a)
        return Location::solid;
      return Location::cut;
    }

    /// Where a cell lies relative to all balls.
    template <typename Placement, typename CellIterator, typename Balls>
    Placement
    place(const CellIterator &cell, const Balls &balls)
    {
      Placement p;
      for (unsigned int k = 0; k < balls.size(); ++k)
        {
          const Location where = locate(cell, balls[k].center, balls[k].radius);
          if (where == Location::solid)
            p.solid = true;
          else if (where == Location::cut)
            {
              ++p.n_cut;
              p.ball = k;
            }
        }
      return p;
    }

    /// A boundary cell's position on a face of the box: its level and its
    /// lower corner in cells of that level (the coarse cells' sides
    /// @p coarse halved that many times), the face's axis left out (0).
    template <int dim>
    using FaceKey = std::pair<int, std::array<long, dim>>;

    template <int dim, typename CellIterator>
    FaceKey<dim>
    face_key(const CellIterator            &cell,
             const unsigned int             axis,
             const std::array<double, dim> &coarse)
    {
      FaceKey<dim> key;
      key.first          = cell->level();
      const double cells = std::ldexp(1., cell->level());
      for (unsigned int d = 0; d < dim; ++d)
        key.second[d] =
          d == axis ? 0 : std::lround(cell->vertex(0)[d] / coarse[d] * cells);
      return key;
    }
  } // namespace



  template <int dim>
  void
  CutMesh<dim>::add_balls_with_images(const std::vector<Point<dim>> &centers,
                                      const std::vector<double>     &radii,
                                      const Settings                &s,
                                      const std::vector<bool>       &periodic)
  {
    // Each particle, wrapped into the box along periodic axes, and its
    // images shifted by one period wherever they come within reach of the
    // box: the surface (the cut cells) and the gap rule (a cell within a
    // few of its sizes of another particle) look that far.
    const double reach = (s.gap_cells + 1.) * std::sqrt(dim) *
                         *std::max_element(coarse.begin(), coarse.end()) *
                         std::ldexp(1., -int(s.global_level));
    for (unsigned int i = 0; i < centers.size(); ++i)
      {
        Point<dim> c = centers[i];
        for (unsigned int d = 0; d < dim; ++d)
          if (periodic[d])
            c[d] -= sides[d] * std::floor(c[d] / sides[d]);
        std::array<int, dim> shift;
        for (unsigned int d = 0; d < dim; ++d)
          shift[d] = periodic[d] ? -1 : 0;
        while (true)
          {
            Ball   b{c, radii[i], i};
            double outside2 = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              {
                b.center[d] += shift[d] * sides[d];
                const double o =
                  std::max({-b.center[d], 0., b.center[d] - sides[d]});
                outside2 += o * o;
              }
            if (std::sqrt(outside2) < b.radius + reach)
              balls.push_back(b);
            unsigned int d = 0;
            while (d < dim && (!periodic[d] || shift[d] == 1))
              {
                if (periodic[d])
                  shift[d] = -1;
                ++d;
              }
            if (d == dim)
              break;
            ++shift[d];
          }
      }
  }



  template <int dim>
  void
  CutMesh<dim>::check_gaps() const
  {
    for (unsigned int k = 0; k < balls.size(); ++k)
      for (unsigned int l = 0; l < k; ++l)
        if (balls[k].owner != balls[l].owner)
          {
            const double gap = (balls[k].center - balls[l].center).norm() -
                               balls[k].radius - balls[l].radius;
            if (!(gap > 0.))
              {
                // Six significant digits, not six decimals: a tiny overlap
                // must not read as -0.000000.
                std::ostringstream m;
                m << "CutStokesInclusion: the gap between particles "
                  << std::min(balls[k].owner, balls[l].owner) << " and "
                  << std::max(balls[k].owner, balls[l].owner) << " is " << gap
                  << "; allowed: > 0";
                throw std::invalid_argument(m.str());
              }
          }
  }



  template <int dim>
  void
  CutMesh<dim>::refine_band(const Settings &s)
  {
    for (unsigned int l = 0; l < s.band_levels; ++l)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          {
            const double     band = s.band_cells * longest_side(cell);
            const Point<dim> x    = cell->center();
            for (const Ball &b : balls)
              if (std::abs((x - b.center).norm() - b.radius) < band)
                {
                  cell->set_refine_flag();
                  break;
                }
          }
        triangulation.execute_coarsening_and_refinement();
      }
  }



  template <int dim>
  void
  CutMesh<dim>::refine_gaps(const Settings          &s,
                            const std::vector<bool> &periodic)
  {
    // A cell cut by two surfaces would need two level sets in one
    // quadrature: refine it until each cut cell meets one surface, and with
    // gap_cells > 0 refine the cut cells near another particle or a wall
    // until the gap has cells across it. Only the cells at the gap are
    // refined: the ghost penalties are assembled across hanging faces too,
    // so a cut cell may have neighbours one level coarser or finer. The
    // triangulation keeps levels within one of each other at vertices, so
    // that the refinement grades away from the gap.
    const int max_level =
      static_cast<int>(s.global_level + s.band_levels + s.max_gap_levels);
    for (unsigned int pass = 0; pass < 100000; ++pass)
      {
        bool flagged = false;
        for (const auto &cell : triangulation.active_cell_iterators())
          {
            const Placement here = place<Placement>(cell, balls);
            if (here.solid || here.n_cut == 0)
              continue;
            bool         near_other = here.n_cut >= 2;
            const double reach =
              (s.gap_cells + 0.5 * std::sqrt(dim)) * longest_side(cell);
            const Point<dim> x = cell->center();
            if (!near_other && s.gap_cells > 0.)
              for (const Ball &b : balls)
                if (b.owner != balls[here.ball].owner &&
                    (x - b.center).norm() - b.radius < reach)
                  near_other = true;
            // A thin gap between a particle and a wall is refined alike.
            if (!near_other && s.gap_cells > 0.)
              for (unsigned int d = 0; d < dim; ++d)
                if (!periodic[d] && std::min(x[d], sides[d] - x[d]) < reach)
                  near_other = true;
            if (!near_other)
              continue;
            if (cell->level() >= max_level)
              {
                if (here.n_cut >= 2)
                  throw std::invalid_argument(
                    "CutStokesInclusion: a cell of size " +
                    std::to_string(longest_side(cell)) +
                    " is still cut by two particles after " +
                    std::to_string(s.max_gap_levels) +
                    " further levels; allowed: wider gaps or a larger "
                    "max_gap_levels");
                continue;
              }
            cell->set_refine_flag();
            ++n_gap_refinements;
            flagged = true;
          }
        if (!flagged)
          break;
        triangulation.execute_coarsening_and_refinement();
      }
  }



  template <int dim>
  CutMesh<dim>::CutMesh(const std::vector<Point<dim>> &centers,
                        const std::vector<double>     &radii,
                        const Settings                &s)
    : triangulation(Triangulation<dim>::limit_level_difference_at_vertices)
  {
    std::vector<double> box(dim, 1.);
    if (!s.box_sides.empty())
      box = s.box_sides;
    if (box.size() != dim)
      throw std::invalid_argument("CutMesh: the box has not dim sides");
    // Coarse cells of about unit size: cubes when the sides are whole
    // numbers, and in any box of sides in [0.75, 1.5) (a side in [1, 1.5)
    // is one cell, in [1.5, 2.5) two, ...), so less than twice as long one
    // way as another.
    std::vector<unsigned int> cells(dim);
    Point<dim>                upper;
    for (unsigned int d = 0; d < dim; ++d)
      {
        if (!(box[d] >= 1.) || !std::isfinite(box[d]))
          throw std::invalid_argument(
            "CutMesh: a side of the box is below 1 (the shortest side is "
            "the length unit) or not finite");
        cells[d] = static_cast<unsigned int>(std::lround(box[d]));
        sides[d] = upper[d] = box[d];
        coarse[d]           = box[d] / cells[d];
      }
    std::vector<bool> periodic(dim, false);
    for (const unsigned int axis : s.periodic_axes)
      periodic[axis] = true;
    add_balls_with_images(centers, radii, s, periodic);
    check_gaps();

    // Cells of about unit size, so that a level is about the same cell
    // size whatever the box, and the face keys below count cells of one
    // size along each axis of a face.
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              cells,
                                              Point<dim>(),
                                              upper,
                                              true);
    triangulation.refine_global(s.global_level);
    refine_band(s);

    refine_gaps(s, periodic);

    // Periodic faces are made to match cell for cell: the coarser side of
    // every mismatch is refined until none is left.
    for (unsigned int pass = 0; pass < 100000; ++pass)
      {
        bool flagged = false;
        for (const unsigned int axis : s.periodic_axes)
          flagged = flag_periodic_mismatch(axis) || flagged;
        if (!flagged)
          break;
        triangulation.execute_coarsening_and_refinement();
      }
    for (const unsigned int axis : s.periodic_axes)
      collect_periodic_pairs(axis);

    placements.resize(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      placements[cell->active_cell_index()] = place<Placement>(cell, balls);
  }



  template <int dim>
  bool
  CutMesh<dim>::flag_periodic_mismatch(const unsigned int axis)
  {
    using Cell = typename Triangulation<dim>::active_cell_iterator;
    std::array<std::map<FaceKey<dim>, Cell>, 2> sides;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (unsigned int side = 0; side < 2; ++side)
        if (cell->at_boundary(2 * axis + side))
          sides[side][face_key<dim>(cell, axis, coarse)] = cell;
    unsigned int flags = 0;
    for (unsigned int side = 0; side < 2; ++side)
      for (const auto &[key, cell] : sides[side])
        {
          (void)cell;
          const auto &other = sides[1 - side];
          if (other.count(key) > 0)
            continue;
          // The other side is coarser here (refine its cell) or finer
          // (its own cells find this one coarser).
          for (int level = key.first - 1; level >= 0; --level)
            {
              FaceKey<dim> coarse = key;
              coarse.first        = level;
              for (unsigned int d = 0; d < dim; ++d)
                coarse.second[d] = key.second[d] >> (key.first - level);
              const auto found = other.find(coarse);
              if (found != other.end())
                {
                  if (!found->second->refine_flag_set())
                    {
                      found->second->set_refine_flag();
                      ++flags;
                    }
                  break;
                }
            }
        }
    n_periodic_refinements += flags;
    return flags > 0;
  }



  template <int dim>
  void
  CutMesh<dim>::collect_periodic_pairs(const unsigned int axis)
  {
    using Cell = typename Triangulation<dim>::active_cell_iterator;
    std::map<FaceKey<dim>, Cell> upper;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->at_boundary(2 * axis + 1))
        upper[face_key<dim>(cell, axis, coarse)] = cell;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->at_boundary(2 * axis))
        {
          const auto found = upper.find(face_key<dim>(cell, axis, coarse));
          if (found == upper.end())
            throw std::logic_error(
              "CutMesh: the periodic faces do not match after refinement");
          periodic_pairs.push_back({axis,
                                    cell->level(),
                                    cell->index(),
                                    found->second->level(),
                                    found->second->index()});
        }
  }



  template <int dim>
  void
  CutMesh<dim>::make_periodicity_constraints(
    const DoFHandler<dim>     &dof_handler,
    AffineConstraints<double> &constraints) const
  {
    using Cell = typename DoFHandler<dim>::active_cell_iterator;
    std::vector<types::global_dof_index> lower_dofs, upper_dofs;
    for (const PeriodicPair &pair : periodic_pairs)
      {
        const Cell  lower(&triangulation,
                         pair.lower_level,
                         pair.lower_index,
                         &dof_handler);
        const Cell  upper(&triangulation,
                         pair.upper_level,
                         pair.upper_index,
                         &dof_handler);
        const auto &fe_lower = lower->get_fe();
        const auto &fe_upper = upper->get_fe();
        if (fe_lower.n_dofs_per_cell() == 0 || fe_upper.n_dofs_per_cell() == 0)
          continue;
        lower_dofs.resize(fe_lower.n_dofs_per_cell());
        upper_dofs.resize(fe_upper.n_dofs_per_cell());
        lower->get_dof_indices(lower_dofs);
        upper->get_dof_indices(upper_dofs);
        const auto        &points_lower = fe_lower.get_unit_support_points();
        const auto        &points_upper = fe_upper.get_unit_support_points();
        const unsigned int a            = pair.axis;
        for (unsigned int i = 0; i < upper_dofs.size(); ++i)
          {
            if (std::abs(points_upper[i][a] - 1.) > 1e-12 ||
                constraints.is_constrained(upper_dofs[i]))
              continue;
            const unsigned int component =
              fe_upper.system_to_component_index(i).first;
            for (unsigned int j = 0; j < lower_dofs.size(); ++j)
              {
                if (std::abs(points_lower[j][a]) > 1e-12 ||
                    fe_lower.system_to_component_index(j).first != component)
                  continue;
                bool same = true;
                for (unsigned int d = 0; d < dim; ++d)
                  if (d != a &&
                      std::abs(points_lower[j][d] - points_upper[i][d]) > 1e-12)
                    same = false;
                if (same && lower_dofs[j] != upper_dofs[i])
                  {
                    constraints.add_line(upper_dofs[i]);
                    constraints.add_entry(upper_dofs[i], lower_dofs[j], 1.);
                    break;
                  }
              }
          }
      }
  }



  template class CutMesh<2>;
  template class CutMesh<3>;
} // namespace Fidus
