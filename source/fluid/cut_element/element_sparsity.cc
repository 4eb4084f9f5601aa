#include <algorithm>
#include <fidus/fluid/cut_element/element_sparsity.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <limits>

namespace Fidus
{
  ElementSparsity::ElementSparsity(const unsigned int               n_dofs,
                                   const AffineConstraints<double> &constraints)
    : n(n_dofs)
    , constraints(constraints)
    , starts{0}
  {}

  void
  ElementSparsity::add_element(const std::vector<types::global_dof_index> &dofs)
  {
    const std::size_t first = columns.size();
    for (const auto i : dofs)
      if (!constraints.is_constrained(i))
        columns.push_back(i);
      else
        for (const auto &entry : *constraints.get_constraint_entries(i))
          columns.push_back(entry.first);
    // U without repeats: an element's columns are added once per row.
    std::sort(columns.begin() + first, columns.end());
    columns.erase(std::unique(columns.begin() + first, columns.end()),
                  columns.end());
    starts.push_back(columns.size());
    for (const auto i : dofs)
      if (constraints.is_constrained(i))
        columns.push_back(i);
    starts.push_back(columns.size());
    columns.insert(columns.end(), dofs.begin(), dofs.end());
    starts.push_back(columns.size());
  }

  std::vector<std::size_t>
  ElementSparsity::row_weights() const
  {
    // A row in U takes U's list (and C's if it is in L too), a row in C
    // takes L's (build()).
    const auto length = [this](const std::size_t e, const unsigned int k) {
      const auto [first, last] = list(e, k);
      return std::size_t(last - first);
    };
    std::vector<std::size_t> weight(n, 0);
    for_each_touch(
      [&](const unsigned int row, const std::size_t e, unsigned char kind) {
        weight[row] += kind == 2 ?
                         length(e, 2) :
                         length(e, 0) + (kind == 1 ? length(e, 1) : 0);
      });
    return weight;
  }

  void
  ElementSparsity::build(RowPattern              &pattern,
                         const std::vector<Keep> &keep,
                         const std::vector<bool> &kept_columns) const
  {
    AssertThrow(keep.empty() || keep.size() == n,
                ExcDimensionMismatch(keep.size(), n));
    AssertThrow(keep.empty() ||
                  std::find(keep.begin(), keep.end(), Keep::flagged) ==
                    keep.end() ||
                  kept_columns.size() == n,
                ExcDimensionMismatch(kept_columns.size(), n));
    // For each row, the elements that touch it and how (for_each_touch()).
    // The pairs are sorted by row (a counting sort), the elements of a row
    // in their order.
    constexpr unsigned int   none = std::numeric_limits<unsigned int>::max();
    std::vector<std::size_t> row_start(n + 1, 0);
    for_each_touch([&](const unsigned int row, std::size_t, unsigned char) {
      ++row_start[row + 1];
    });
    for (unsigned int i = 0; i < n; ++i)
      row_start[i + 1] += row_start[i];
    std::vector<std::size_t>   touch_element(row_start[n]);
    std::vector<unsigned char> touch_kind(row_start[n]);
    {
      std::vector<std::size_t> next(row_start.begin(), row_start.end() - 1);
      for_each_touch(
        [&](const unsigned int row, const std::size_t e, unsigned char kind) {
          touch_element[next[row]] = e;
          touch_kind[next[row]++]  = kind;
        });
    }

    // Each row's columns: the lists of its elements without repeats, on
    // four ranges of rows per thread (the rows near the particles are the
    // long ones), counted first so that the pattern's columns are
    // allocated once.
    std::vector<std::size_t>  col_start(n + 1, 0);
    std::vector<unsigned int> row_columns;
    const auto row_lists = [&](const unsigned int row, const auto &g) {
      for (std::size_t t = row_start[row]; t < row_start[row + 1]; ++t)
        {
          const std::size_t e = touch_element[t];
          if (touch_kind[t] == 2)
            g(list(e, 2));
          else
            {
              g(list(e, 0));
              if (touch_kind[t] == 1)
                g(list(e, 1));
            }
        }
    };
    for (const bool fill : {false, true})
      {
        if (fill)
          {
            for (unsigned int i = 0; i < n; ++i)
              col_start[i + 1] += col_start[i];
            row_columns.resize(col_start[n]);
          }
        on_row_ranges(n,
                      4,
                      [&](const unsigned int first, const unsigned int last) {
                        std::vector<unsigned int> seen(n, none);
                        for (unsigned int row = first; row < last; ++row)
                          {
                            std::size_t to = fill ? col_start[row] : 0;
                            const Keep  row_keeps =
                              keep.empty() ? Keep::all : keep[row];
                            const bool partial = row_keeps == Keep::flagged;
                            // (RowPattern adds the diagonal.)
                            if (row_keeps != Keep::diagonal)
                              row_lists(row, [&](const auto &range) {
                                for (auto p = range.first; p != range.second;
                                     ++p)
                                  if (seen[*p] != row)
                                    {
                                      seen[*p] = row;
                                      if (partial && !kept_columns[*p])
                                        continue;
                                      if (fill)
                                        row_columns[to] = *p;
                                      ++to;
                                    }
                              });
                            if (!fill)
                              col_start[row + 1] = to;
                          }
                      });
      }

    pattern.fill_from_rows(n, n, row_columns, col_start);
  }
} // namespace Fidus
