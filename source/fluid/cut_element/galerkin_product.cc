#include <algorithm>
#include <cstddef>
#include <fidus/fluid/cut_element/component_coupling.h>
#include <fidus/fluid/cut_element/galerkin_product.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <fidus/fluid/cut_element/sparse_rows.h>
#include <vector>

namespace Fidus
{
  namespace
  {
    /// @p m's entries, row by row.
    SparseRows
    rows_of(const SparseMatrix<double> &m)
    {
      SparseRows r;
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
    const SparseRows product = [&]() {
      const SparseRows p_rows = rows_of(p);
      // A P, reading A in place (it is the largest matrix of the hierarchy).
      const SparseRows ap = multiply(
        a.m(),
        [&a, &component](const unsigned int i, const auto &f) {
          for (auto e = a.begin(i); e != a.end(i); ++e)
            if (couples_within_component(component, i, e->column()))
              f(e->column(), e->value());
        },
        p_rows);
      const SparseRows pt = transpose(p_rows);
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
