#ifndef fidus_fluid_cut_element_sparse_rows_h
#define fidus_fluid_cut_element_sparse_rows_h

#include <cstddef>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <limits>
#include <vector>

namespace Fidus
{
  /**
   * A sparse matrix in compressed rows, columns unsorted within a row: the
   * intermediate products of the cut element's Galerkin products
   * (galerkin_product(), distributed_galerkin_product()).
   */
  struct SparseRows
  {
    unsigned int              n_rows = 0, n_cols = 0;
    std::vector<std::size_t>  start{0};
    std::vector<unsigned int> column;
    std::vector<double>       value;
  };

  /// The transpose of @p m (a counting sort by column).
  inline SparseRows
  transpose(const SparseRows &m)
  {
    SparseRows t;
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
   * X Y, row by row (Gustavson's algorithm): row i of the product
   * accumulates, over the entries x_ij of row i of X, x_ij times row j of
   * Y. @p x_row(i, f) calls f(j, x_ij) for those entries. A first pass
   * counts each row's columns, so that the product is allocated once at its
   * size (a growing array would double it). The rows are split among the
   * threads; each row is summed in the same order on any number of them.
   */
  template <typename XRow>
  SparseRows
  multiply(const unsigned int n_rows, const XRow &x_row, const SparseRows &y)
  {
    constexpr unsigned int none = std::numeric_limits<unsigned int>::max();
    SparseRows             r;
    r.n_rows = n_rows;
    r.n_cols = y.n_cols;
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
    on_row_ranges(n_rows,
                  1,
                  [&](const unsigned int first, const unsigned int last) {
                    std::vector<double>       sum(y.n_cols, 0.);
                    std::vector<unsigned int> last_row(y.n_cols, none);
                    std::vector<unsigned int> touched;
                    for (unsigned int i = first; i < last; ++i)
                      {
                        touched.clear();
                        x_row(i, [&](const unsigned int j, const double x_ij) {
                          for (std::size_t k = y.start[j]; k < y.start[j + 1];
                               ++k)
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
} // namespace Fidus

#endif
