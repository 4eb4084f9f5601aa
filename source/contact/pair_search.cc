#include <fidus/contact/contact_error.h>
#include <fidus/contact/pair_search.h>

// Boost 1.74's Boost.Math (pulled in by Boost.Geometry) includes one of its
// own deprecated headers; the note it prints is not about fidus code.
#ifndef BOOST_ALLOW_DEPRECATED_HEADERS
#  define BOOST_ALLOW_DEPRECATED_HEADERS
#endif
#include <algorithm>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <limits>

namespace Fidus::Contact
{
  namespace
  {
    /// @p x wrapped into [0, L) for a period L > 0.
    double
    wrap_into_period(const double x, const double L)
    {
      const double w = x - L * std::floor(x / L);
      // Rounding can give exactly L for a tiny negative x.
      return (w >= L || w < 0.) ? 0. : w;
    }
  } // namespace



  PairSearch::PairSearch(const unsigned int     dimension,
                         const PairSearchMethod method)
    : dimension(dimension)
    , method(method)
  {
    if (dimension != 2 && dimension != 3)
      throw ContactError("pair search: dimension must be 2 or 3, got " +
                         std::to_string(dimension));
  }



  void
  PairSearch::set_periodicity(const std::array<double, 3> &periods)
  {
    for (unsigned int d = 0; d < 3; ++d)
      {
        if (!(periods[d] >= 0.) || !std::isfinite(periods[d]))
          throw ContactError("pair search: the period in direction " +
                             std::to_string(d) + " is " +
                             std::to_string(periods[d]) +
                             ": it must be > 0 (periodic) or 0 (not "
                             "periodic)");
        if (d >= dimension && periods[d] != 0.)
          throw ContactError("pair search: a period in direction " +
                             std::to_string(d) + " is given in " +
                             std::to_string(dimension) +
                             "D, where that direction does not exist");
      }
    period = periods;
  }



  void
  PairSearch::find_pairs(const std::vector<Vec3>   &positions,
                         const std::vector<double> &radii,
                         const double               cutoff,
                         std::vector<Pair>         &pairs)
  {
    pairs.clear();
    if (positions.size() < 2)
      return;
    if (method == PairSearchMethod::rtree)
      {
        if (dimension == 2)
          find_pairs_rtree<2>(positions, radii, cutoff, pairs);
        else
          find_pairs_rtree<3>(positions, radii, cutoff, pairs);
      }
    else
      find_pairs_cell_list(positions, radii, cutoff, pairs);
  }



  /// The uniform grid of the cell list: which directions are periodic,
  /// where the cells start, how large they are and how many there are.
  struct internal::CellGrid
  {
    std::array<bool, 3>        periodic{{false, false, false}};
    bool                       any_periodic = false;
    std::array<double, 3>      period{{0., 0., 0.}};
    Vec3                       lo{{0., 0., 0.}};
    Vec3                       cell_size{{0., 0., 0.}};
    std::array<std::size_t, 3> nc{{1, 1, 1}};
    std::size_t                n_cells = 1;

    /// @p x wrapped into [0, L) if direction @p d is periodic, else @p x.
    double
    wrapped(const double x, const unsigned d) const
    {
      return periodic[d] ? wrap_into_period(x, period[d]) : x;
    }
  };



  namespace
  {
    using internal::CellGrid;



    /// The cell grid for the given particles and cut-off: cells large
    /// enough that only neighbouring cells can hold a partner, but not so
    /// many that the grid outgrows the number of particles.
    CellGrid
    build_cell_grid(const std::vector<Vec3>     &positions,
                    const std::vector<double>   &radii,
                    const double                 cutoff,
                    const unsigned               dim,
                    const std::array<double, 3> &period)
    {
      const std::size_t n = positions.size();
      CellGrid          grid;
      grid.period = period;

      // In a periodic direction the particles are binned by their coordinate
      // wrapped into [0, L) (the box origin does not matter, only the
      // period), and the cells tile [0, L) exactly so that the neighbour of
      // the last cell is the first one.
      std::array<bool, 3> &periodic = grid.periodic;
      for (unsigned d = 0; d < dim; ++d)
        {
          periodic[d]       = period[d] > 0.;
          grid.any_periodic = grid.any_periodic || periodic[d];
        }

      double a_max = 0.;
      Vec3   lo{{0., 0., 0.}}, hi{{0., 0., 0.}};
      for (unsigned d = 0; d < dim; ++d)
        {
          lo[d] = std::numeric_limits<double>::max();
          hi[d] = -std::numeric_limits<double>::max();
        }
      for (std::size_t i = 0; i < n; ++i)
        {
          a_max = std::max(a_max, radii[i]);
          for (unsigned d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], positions[i][d]);
              hi[d] = std::max(hi[d], positions[i][d]);
            }
        }
      for (unsigned d = 0; d < dim; ++d)
        if (periodic[d])
          {
            lo[d] = 0.;
            hi[d] = period[d];
          }

      // Any pair with gap below the cut-off has its centres closer than
      // 2 a_max + cutoff, so with cells at least that large only the 3^d
      // neighbouring cells can hold a partner. Larger cells are still
      // correct; they are used when the particles are so spread out that the
      // grid would hold many more cells than particles (memory and time
      // would then grow with the box, not with N).
      double h = std::max(2. * a_max + std::max(cutoff, 0.), 1e-300);
      // Cells along a periodic direction: as many as fit, at least one;
      // their size L / n_cells is then >= h.
      auto n_periodic_cells = [&](const unsigned d, const double size) {
        return std::max(1., std::floor(period[d] / size));
      };
      std::array<std::size_t, 3> &nc = grid.nc;
      for (int attempt = 0; attempt < 64; ++attempt)
        {
          double total = 1.;
          for (unsigned d = 0; d < dim; ++d)
            total *= periodic[d] ? n_periodic_cells(d, h) :
                                   std::floor((hi[d] - lo[d]) / h) + 1.;
          const double max_cells = 2. * static_cast<double>(n) + 64.;
          if (total <= max_cells)
            break;
          h *= std::max(1.01, std::pow(total / max_cells, 1. / dim));
        }
      Vec3 cell_size{{h, h, h}};
      for (unsigned d = 0; d < dim; ++d)
        if (periodic[d])
          {
            nc[d] = static_cast<std::size_t>(n_periodic_cells(d, h));
            // Guard against L / n rounding to just below h.
            while (nc[d] > 1 && period[d] / static_cast<double>(nc[d]) < h)
              --nc[d];
            cell_size[d] = period[d] / static_cast<double>(nc[d]);
          }
        else
          nc[d] = static_cast<std::size_t>(std::floor((hi[d] - lo[d]) / h)) + 1;
      grid.n_cells   = nc[0] * nc[1] * nc[2];
      grid.lo        = lo;
      grid.cell_size = cell_size;
      return grid;
    }



    /// The offsets of the neighbour cells that a cell visits, so that each
    /// unordered pair of cells is visited once.
    std::vector<std::array<int, 3>>
    half_stencil(const unsigned dim, const bool any_periodic)
    {
      // Half stencil: each unordered pair of cells is visited once. Without
      // periodic directions these are the lexicographically positive offsets
      // in (z, y, x) order. With periodic directions a cell instead visits,
      // among all 3^d - 1 wrapped neighbours, those with a larger index than
      // its own (the same set without periodicity, in the same order).
      std::vector<std::array<int, 3>> stencil;
      for (int dz = (dim == 3 ? -1 : 0); dz <= (dim == 3 ? 1 : 0); ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (any_periodic ? (dx != 0 || dy != 0 || dz != 0) :
                               (dz > 0 || (dz == 0 && dy > 0) ||
                                (dz == 0 && dy == 0 && dx > 0)))
              stencil.push_back({{dx, dy, dz}});
      return stencil;
    }



    /// The cells that cell @p c (at @p index) visits through @p stencil,
    /// each once, into @p neighbours.
    void
    collect_neighbour_cells(const CellGrid                        &grid,
                            const std::vector<std::array<int, 3>> &stencil,
                            const std::array<std::size_t, 3>      &index,
                            const std::size_t                      c,
                            std::vector<std::size_t>              &neighbours)
    {
      const auto &nc = grid.nc;
      neighbours.clear();
      for (const auto &s : stencil)
        {
          std::size_t c2     = 0;
          bool        inside = true;
          for (int d = 2; d >= 0 && inside; --d)
            {
              long       k = static_cast<long>(index[d]) + s[d];
              const long m = static_cast<long>(nc[d]);
              if (grid.periodic[d])
                k = (k + m) % m;
              else if (k < 0 || k >= m)
                inside = false;
              c2 = c2 * nc[d] + static_cast<std::size_t>(k);
            }
          if (!inside)
            continue;
          // With fewer than 3 cells along a periodic direction,
          // different offsets reach the same cell (or the cell
          // itself): each is kept once, else its pairs would be
          // found twice.
          if (grid.any_periodic &&
              (c2 <= c || std::find(neighbours.begin(), neighbours.end(), c2) !=
                            neighbours.end()))
            continue;
          neighbours.push_back(c2);
        }
    }
  } // namespace



  void
  PairSearch::sort_into_cells(const std::vector<Vec3>   &positions,
                              const std::vector<double> &radii,
                              const CellGrid            &grid)
  {
    const std::size_t n   = positions.size();
    const unsigned    dim = dimension;
    const auto       &nc  = grid.nc;

    // Counting sort of the particles into the cells.
    cell_of.resize(n);
    cell_start.assign(grid.n_cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      {
        std::size_t c = 0;
        for (int d = static_cast<int>(dim) - 1; d >= 0; --d)
          {
            auto k = static_cast<std::size_t>(
              (grid.wrapped(positions[i][d], d) - grid.lo[d]) /
              grid.cell_size[d]);
            k = std::min(k, nc[d] - 1);
            c = c * nc[d] + k;
          }
        cell_of[i] = static_cast<std::uint32_t>(c);
        ++cell_start[c + 1];
      }
    for (std::size_t c = 0; c < grid.n_cells; ++c)
      cell_start[c + 1] += cell_start[c];
    sorted_index.resize(n);
    sorted_position.resize(n);
    sorted_radius.resize(n);
    {
      std::vector<std::uint32_t> fill(cell_start.begin(), cell_start.end() - 1);
      for (std::size_t i = 0; i < n; ++i)
        {
          const std::uint32_t slot = fill[cell_of[i]]++;
          sorted_index[slot]       = static_cast<std::uint32_t>(i);
          for (unsigned d = 0; d < 3; ++d)
            sorted_position[slot][d] =
              d < dim ? grid.wrapped(positions[i][d], d) : positions[i][d];
          sorted_radius[slot] = radii[i];
        }
    }
  }



  template <typename Close>
  void
  PairSearch::scan_cells(const CellGrid                        &grid,
                         const std::vector<std::array<int, 3>> &stencil,
                         const Close                           &close,
                         std::vector<Pair>                     &pairs) const
  {
    const auto &nc  = grid.nc;
    auto        add = [&](const std::uint32_t p, const std::uint32_t q) {
      const std::uint32_t i = sorted_index[p], j = sorted_index[q];
      pairs.emplace_back(std::min(i, j), std::max(i, j));
    };

    std::vector<std::size_t> neighbours;
    neighbours.reserve(stencil.size());
    for (std::size_t iz = 0; iz < nc[2]; ++iz)
      for (std::size_t iy = 0; iy < nc[1]; ++iy)
        for (std::size_t ix = 0; ix < nc[0]; ++ix)
          {
            const std::size_t c     = ix + nc[0] * (iy + nc[1] * iz);
            const auto        begin = cell_start[c], end = cell_start[c + 1];
            if (begin == end)
              continue;
            for (auto p = begin; p < end; ++p)
              for (auto q = p + 1; q < end; ++q)
                if (close(p, q))
                  add(p, q);

            collect_neighbour_cells(grid,
                                    stencil,
                                    {{ix, iy, iz}},
                                    c,
                                    neighbours);

            for (const std::size_t c2 : neighbours)
              {
                const auto begin2 = cell_start[c2], end2 = cell_start[c2 + 1];
                for (auto p = begin; p < end; ++p)
                  for (auto q = begin2; q < end2; ++q)
                    if (close(p, q))
                      add(p, q);
              }
          }
  }



  void
  PairSearch::find_pairs_cell_list(const std::vector<Vec3>   &positions,
                                   const std::vector<double> &radii,
                                   const double               cutoff,
                                   std::vector<Pair>         &pairs)
  {
    const unsigned dim = dimension;

    const CellGrid grid =
      build_cell_grid(positions, radii, cutoff, dim, period);
    sort_into_cells(positions, radii, grid);
    const std::vector<std::array<int, 3>> stencil =
      half_stencil(dim, grid.any_periodic);

    // The scan over the cells, for a distance test @p close (with or
    // without minimum image, so that the common non-periodic case does not
    // pay for it).
    if (grid.any_periodic)
      scan_cells(
        grid,
        stencil,
        [&](const std::uint32_t p, const std::uint32_t q) {
          const double reach = sorted_radius[p] + sorted_radius[q] + cutoff;
          double       r2    = 0.;
          for (unsigned d = 0; d < dim; ++d)
            {
              const double dx =
                minimum_image(sorted_position[q][d] - sorted_position[p][d],
                              period[d]);
              r2 += dx * dx;
            }
          return reach > 0. && r2 < reach * reach;
        },
        pairs);
    else
      scan_cells(
        grid,
        stencil,
        [&](const std::uint32_t p, const std::uint32_t q) {
          const double reach = sorted_radius[p] + sorted_radius[q] + cutoff;
          double       r2    = 0.;
          for (unsigned d = 0; d < dim; ++d)
            {
              const double dx = sorted_position[q][d] - sorted_position[p][d];
              r2 += dx * dx;
            }
          return reach > 0. && r2 < reach * reach;
        },
        pairs);
  }



  template <int dim>
  void
  PairSearch::find_pairs_rtree(const std::vector<Vec3>   &positions,
                               const std::vector<double> &radii,
                               const double               cutoff,
                               std::vector<Pair>         &pairs) const
  {
    namespace bg  = boost::geometry;
    namespace bgi = boost::geometry::index;
    using Point   = bg::model::point<double, dim, bg::cs::cartesian>;
    using Box     = bg::model::box<Point>;
    using Value   = std::pair<Box, std::uint32_t>;

    const std::size_t n = positions.size();

    // Periodic directions: the boxes are built around the centres wrapped
    // into [0, L); the partner of particle i through a periodic face is then
    // found by querying with the search box of i translated by -L, 0 or +L
    // (the minimum image of a difference of wrapped coordinates is one of
    // these three). A translation is tried only if it can reach a box.
    std::array<bool, dim> periodic;
    bool                  any_periodic = false;
    double                a_max        = 0.;
    for (unsigned d = 0; d < dim; ++d)
      {
        periodic[d]  = period[d] > 0.;
        any_periodic = any_periodic || periodic[d];
      }
    for (std::size_t i = 0; i < n; ++i)
      a_max = std::max(a_max, radii[i]);
    std::vector<Vec3> wrapped_storage;
    if (any_periodic)
      {
        wrapped_storage = positions;
        for (auto &x : wrapped_storage)
          for (unsigned d = 0; d < dim; ++d)
            if (periodic[d])
              x[d] = wrap_into_period(x[d], period[d]);
      }
    const std::vector<Vec3> &x = any_periodic ? wrapped_storage : positions;

    auto box_of = [&](const std::size_t i, const double extra, const Vec3 &t) {
      Point lo, hi;
      lo.template set<0>(x[i][0] + t[0] - radii[i] - extra);
      hi.template set<0>(x[i][0] + t[0] + radii[i] + extra);
      lo.template set<1>(x[i][1] + t[1] - radii[i] - extra);
      hi.template set<1>(x[i][1] + t[1] + radii[i] + extra);
      if constexpr (dim == 3)
        {
          lo.template set<2>(x[i][2] + t[2] - radii[i] - extra);
          hi.template set<2>(x[i][2] + t[2] + radii[i] + extra);
        }
      return Box(lo, hi);
    };
    const Vec3 no_shift{{0., 0., 0.}};

    std::vector<Value> values;
    values.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      values.emplace_back(box_of(i, 0., no_shift),
                          static_cast<std::uint32_t>(i));
    // The range constructor bulk-loads (packs) the tree, much faster than
    // inserting one box at a time.
    const bgi::rtree<Value, bgi::rstar<16>> tree(values.begin(), values.end());

    std::vector<Value>         hits;
    std::vector<std::uint32_t> partners;
    std::vector<Vec3>          shifts;
    const double               extra = std::max(cutoff, 0.);
    for (std::size_t i = 0; i < n; ++i)
      {
        hits.clear();
        if (!any_periodic)
          tree.query(bgi::intersects(box_of(i, extra, no_shift)),
                     std::back_inserter(hits));
        else
          {
            // Translations of the search box that can reach a box of the
            // tree, whose boxes lie within [-a_max, L + a_max].
            shifts.assign(1, no_shift);
            for (unsigned d = 0; d < dim; ++d)
              if (periodic[d])
                {
                  const double reach = radii[i] + extra;
                  const double L     = period[d];
                  const auto   m     = shifts.size();
                  for (const double s : {-1., 1.})
                    if ((s > 0. && x[i][d] - reach < a_max) ||
                        (s < 0. && x[i][d] + reach > L - a_max))
                      for (std::size_t k = 0; k < m; ++k)
                        {
                          Vec3 t = shifts[k];
                          t[d]   = s * L;
                          shifts.push_back(t);
                        }
                }
            for (const auto &t : shifts)
              tree.query(bgi::intersects(box_of(i, extra, t)),
                         std::back_inserter(hits));
          }

        // Several translations can hit the same partner (small periods):
        // keep each once, in increasing order.
        partners.clear();
        for (const auto &hit : hits)
          if (hit.second > i)
            partners.push_back(hit.second);
        if (any_periodic)
          {
            std::sort(partners.begin(), partners.end());
            partners.erase(std::unique(partners.begin(), partners.end()),
                           partners.end());
          }
        for (const std::uint32_t j : partners)
          {
            double r2 = 0.;
            for (unsigned d = 0; d < dim; ++d)
              {
                const double dx = minimum_image(x[j][d] - x[i][d], period[d]);
                r2 += dx * dx;
              }
            const double reach = radii[i] + radii[j] + cutoff;
            if (reach > 0. && r2 < reach * reach)
              pairs.emplace_back(static_cast<std::uint32_t>(i), j);
          }
      }
  }
} // namespace Fidus::Contact
