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



  void
  PairSearch::find_pairs_cell_list(const std::vector<Vec3>   &positions,
                                   const std::vector<double> &radii,
                                   const double               cutoff,
                                   std::vector<Pair>         &pairs)
  {
    const std::size_t n   = positions.size();
    const unsigned    dim = dimension;

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

    // Any pair with gap below the cut-off has its centres closer than
    // 2 a_max + cutoff, so with cells at least that large only the 3^d
    // neighbouring cells can hold a partner. Larger cells are still correct;
    // they are used when the particles are so spread out that the grid would
    // hold many more cells than particles (memory and time would then grow
    // with the box, not with N).
    double h = std::max(2. * a_max + std::max(cutoff, 0.), 1e-300);
    std::array<std::size_t, 3> nc{{1, 1, 1}};
    for (int attempt = 0; attempt < 64; ++attempt)
      {
        double total = 1.;
        for (unsigned d = 0; d < dim; ++d)
          total *= std::floor((hi[d] - lo[d]) / h) + 1.;
        const double max_cells = 2. * static_cast<double>(n) + 64.;
        if (total <= max_cells)
          break;
        h *= std::max(1.01, std::pow(total / max_cells, 1. / dim));
      }
    for (unsigned d = 0; d < dim; ++d)
      nc[d] = static_cast<std::size_t>(std::floor((hi[d] - lo[d]) / h)) + 1;
    const std::size_t n_cells = nc[0] * nc[1] * nc[2];

    // Counting sort of the particles into the cells.
    cell_of.resize(n);
    cell_start.assign(n_cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      {
        std::size_t c = 0;
        for (int d = static_cast<int>(dim) - 1; d >= 0; --d)
          {
            auto k = static_cast<std::size_t>((positions[i][d] - lo[d]) / h);
            k      = std::min(k, nc[d] - 1);
            c      = c * nc[d] + k;
          }
        cell_of[i] = static_cast<std::uint32_t>(c);
        ++cell_start[c + 1];
      }
    for (std::size_t c = 0; c < n_cells; ++c)
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
          sorted_position[slot]    = positions[i];
          sorted_radius[slot]      = radii[i];
        }
    }

    // Half stencil: each unordered pair of cells is visited once.
    std::vector<std::array<int, 3>> stencil;
    for (int dz = (dim == 3 ? -1 : 0); dz <= (dim == 3 ? 1 : 0); ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dz > 0 || (dz == 0 && dy > 0) || (dz == 0 && dy == 0 && dx > 0))
            stencil.push_back({{dx, dy, dz}});

    auto close = [&](const std::uint32_t p, const std::uint32_t q) {
      const double reach = sorted_radius[p] + sorted_radius[q] + cutoff;
      double       r2    = 0.;
      for (unsigned d = 0; d < dim; ++d)
        {
          const double dx = sorted_position[q][d] - sorted_position[p][d];
          r2 += dx * dx;
        }
      return reach > 0. && r2 < reach * reach;
    };
    auto add = [&](const std::uint32_t p, const std::uint32_t q) {
      const std::uint32_t i = sorted_index[p], j = sorted_index[q];
      pairs.emplace_back(std::min(i, j), std::max(i, j));
    };

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
            for (const auto &s : stencil)
              {
                const long jx = static_cast<long>(ix) + s[0];
                const long jy = static_cast<long>(iy) + s[1];
                const long jz = static_cast<long>(iz) + s[2];
                if (jx < 0 || jy < 0 || jz < 0 ||
                    jx >= static_cast<long>(nc[0]) ||
                    jy >= static_cast<long>(nc[1]) ||
                    jz >= static_cast<long>(nc[2]))
                  continue;
                const std::size_t c2 =
                  jx + nc[0] * (jy + nc[1] * static_cast<std::size_t>(jz));
                const auto begin2 = cell_start[c2], end2 = cell_start[c2 + 1];
                for (auto p = begin; p < end; ++p)
                  for (auto q = begin2; q < end2; ++q)
                    if (close(p, q))
                      add(p, q);
              }
          }
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

    const std::size_t n      = positions.size();
    auto              box_of = [&](const std::size_t i, const double extra) {
      Point lo, hi;
      lo.template set<0>(positions[i][0] - radii[i] - extra);
      hi.template set<0>(positions[i][0] + radii[i] + extra);
      lo.template set<1>(positions[i][1] - radii[i] - extra);
      hi.template set<1>(positions[i][1] + radii[i] + extra);
      if constexpr (dim == 3)
        {
          lo.template set<2>(positions[i][2] - radii[i] - extra);
          hi.template set<2>(positions[i][2] + radii[i] + extra);
        }
      return Box(lo, hi);
    };

    std::vector<Value> values;
    values.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      values.emplace_back(box_of(i, 0.), static_cast<std::uint32_t>(i));
    // The range constructor bulk-loads (packs) the tree, much faster than
    // inserting one box at a time.
    const bgi::rtree<Value, bgi::rstar<16>> tree(values.begin(), values.end());

    std::vector<Value> hits;
    for (std::size_t i = 0; i < n; ++i)
      {
        hits.clear();
        tree.query(bgi::intersects(box_of(i, std::max(cutoff, 0.))),
                   std::back_inserter(hits));
        for (const auto &hit : hits)
          {
            const std::uint32_t j = hit.second;
            if (j <= i)
              continue;
            double r2 = 0.;
            for (unsigned d = 0; d < dim; ++d)
              {
                const double dx = positions[j][d] - positions[i][d];
                r2 += dx * dx;
              }
            const double reach = radii[i] + radii[j] + cutoff;
            if (reach > 0. && r2 < reach * reach)
              pairs.emplace_back(static_cast<std::uint32_t>(i), j);
          }
      }
  }
} // namespace Fidus::Contact
