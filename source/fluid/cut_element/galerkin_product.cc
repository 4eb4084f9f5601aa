#include <algorithm>
#include <cstddef>
#include <fidus/fluid/cut_element/component_coupling.h>
#include <fidus/fluid/cut_element/galerkin_product.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <limits>
#include <vector>

namespace Fidus
{
  namespace
  {
    /// A sparse matrix in compressed rows, columns unsorted within a row.
    struct Rows
    {
      unsigned int              n_rows = 0, n_cols = 0;
      std::vector<std::size_t>  start{0};
      std::vector<unsigned int> column;
      std::vector<double>       value;
    };

    /// @p m's entries, row by row.
    Rows
    rows_of(const SparseMatrix<double> &m)
    {
      Rows r;
      r.n_rows = m.m();
      r.n_cols = m.n();
      r.start.reserve(r.n_rows + 1);
      r.column.reserve(m.n_nonzero_elements());
      r.value.reserve(m.n_nonzero_elements());
      for (unsigned int i = 0; i < r.n_rows; ++i)
        {
          for (auto e = m.begin(i); e != m.end(i); ++e)
            {
              r.column.push_back(e->column());
              r.value.push_back(e->value());
            }
          r.start.push_back(r.column.size());
        }
      return r;
    }

    /// The transpose of @p m (a counting sort by column).
    Rows
    transpose(const Rows &m)
    {
      Rows t;
      t.n_rows = m.n_cols;
      t.n_cols = m.n_rows;
      t.start.assign(t.n_rows + 1, 0);
      for (const unsigned int j : m.column)
        ++t.start[j + 1];
      for (unsigned int j = 0; j < t.n_rows; ++j)
        t.start[j + 1] += t.start[j];
      t.column.resize(m.column.size());
      t.value.resize(m.value.size());
      std::vector<std::size_t> next(t.start.begin(), t.start.end() - 1);
      for (unsigned int i = 0; i < m.n_rows; ++i)
        for (std::size_t k = m.start[i]; k < m.start[i + 1]; ++k)
          {
            const std::size_t to = next[m.column[k]]++;
            t.column[to]         = i;
            t.value[to]          = m.value[k];
          }
      return t;
    }

    /**
     * X Y, row by row: row i of the product accumulates, over the entries
     * x_ij of row i of X, x_ij times row j of Y. @p x_row(i, f) calls
     * f(j, x_ij) for those entries. The rows are split among the threads;
     * each row is summed in the same order on any number of them.
     */
    template <typename XRow>
    Rows
    multiply(const unsigned int n_rows, const XRow &x_row, const Rows &y)
    {
      constexpr unsigned int none = std::numeric_limits<unsigned int>::max();
      Rows                   r;
      r.n_rows = n_rows;
      r.n_cols = y.n_cols;
      // A first pass counts each row's columns, so that the product is
      // allocated once at its size (a growing array would double it).
      r.start.assign(n_rows + 1, 0);
      on_row_ranges(n_rows,
                    1,
                    [&](const unsigned int first, const unsigned int last) {
                      std::vector<unsigned int> last_row(y.n_cols, none);
                      for (unsigned int i = first; i < last; ++i)
                        x_row(i, [&](const unsigned int j, const double) {
                          for (std::size_t k = y.start[j]; k < y.start[j + 1];
                               ++k)
                            if (last_row[y.column[k]] != i)
                              {
                                last_row[y.column[k]] = i;
                                ++r.start[i + 1];
                              }
                        });
                    });
      for (unsigned int i = 0; i < n_rows; ++i)
        r.start[i + 1] += r.start[i];
      r.column.resize(r.start[n_rows]);
      r.value.resize(r.start[n_rows]);
      on_row_ranges(
        n_rows,
        1,
        [&](const unsigned int first, const unsigned int last) {
          std::vector<double>       sum(y.n_cols, 0.);
          std::vector<unsigned int> last_row(y.n_cols, none);
          std::vector<unsigned int> touched;
          for (unsigned int i = first; i < last; ++i)
            {
              touched.clear();
              x_row(i, [&](const unsigned int j, const double x_ij) {
                for (std::size_t k = y.start[j]; k < y.start[j + 1]; ++k)
                  {
                    const unsigned int col = y.column[k];
                    if (last_row[col] != i)
                      {
                        last_row[col] = i;
                        sum[col]      = 0.;
                        touched.push_back(col);
                      }
                    sum[col] += x_ij * y.value[k];
                  }
              });
              std::size_t to = r.start[i];
              for (const unsigned int col : touched)
                {
                  r.column[to] = col;
                  r.value[to]  = sum[col];
                  ++to;
                }
            }
        });
      return r;
    }

  } // namespace



  void
  galerkin_product(const SparseMatrix<double>       &a,
                   const SparseMatrix<double>       &p,
                   RowPattern                       &pattern,
                   SparseMatrix<double>             &c,
                   const std::vector<unsigned char> &component)
  {
    Assert(component.empty() || component.size() == a.m(),
           ExcDimensionMismatch(component.size(), a.m()));
    // The intermediate products are released before C is allocated.
    const Rows product = [&]() {
      const Rows p_rows = rows_of(p);
      // A P, reading A in place (it is the largest matrix of the hierarchy).
      const Rows ap = multiply(
        a.m(),
        [&a, &component](const unsigned int i, const auto &f) {
          for (auto e = a.begin(i); e != a.end(i); ++e)
            if (couples_within_component(component, i, e->column()))
              f(e->column(), e->value());
        },
        p_rows);
      const Rows pt = transpose(p_rows);
      return multiply(
        pt.n_rows,
        [&pt](const unsigned int i, const auto &f) {
          for (std::size_t k = pt.start[i]; k < pt.start[i + 1]; ++k)
            f(pt.column[k], pt.value[k]);
        },
        ap);
    }();

    // With every diagonal entry, as the multigrid needs.
    pattern.fill_from_rows(product.n_rows,
                           product.n_cols,
                           product.column,
                           product.start);
    c.reinit(pattern);
    on_row_ranges(product.n_rows,
                  1,
                  [&](const unsigned int first, const unsigned int last) {
                    std::vector<double> row_values(product.n_cols, 0.);
                    for (unsigned int i = first; i < last; ++i)
                      {
                        for (std::size_t k = product.start[i];
                             k < product.start[i + 1];
                             ++k)
                          row_values[product.column[k]] = product.value[k];
                        for (auto e = c.begin(i); e != c.end(i); ++e)
                          {
                            e->value()              = row_values[e->column()];
                            row_values[e->column()] = 0.;
                          }
                      }
                  });
  }
} // namespace Fidus
