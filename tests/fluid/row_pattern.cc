// RowPattern (the cut element's sparsity patterns, filled on the threads)
// against deal.II's SparsityPattern::copy_from on the same rows: a square
// pattern (rows with and without their diagonal, empty rows, unsorted
// columns) and a rectangular one. The two must be the same compressed
// pattern: every row's columns in the same order (the diagonal first in
// the square one), the same entries and row lengths, the same lookups,
// and a matrix on each must multiply alike. The rows are filled in more
// ranges than there are threads, so the ranges' seams are crossed. Both
// fills are checked: fill() from the unsorted rows, and fill_ordered()
// from the row lengths and each row's columns in order (without the
// diagonal of the square pattern).

#include "../fidus_test.h"

#include <algorithm>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/row_pattern.h>
#include <random>

using namespace dealii;
using namespace FidusTest;
using Fidus::RowPattern;

namespace
{
  /// @p built against @p expected, both from @p rows.
  void
  compare(const std::string                            &name,
          const SparsityPattern                        &expected,
          const SparsityPattern                        &built,
          const std::vector<std::vector<unsigned int>> &rows)
  {
    const unsigned int m = expected.n_rows(), n = expected.n_cols();
    unsigned int differing_rows = 0, with_diagonal = 0, missing_lookups = 0;
    for (unsigned int i = 0; i < m; ++i)
      {
        std::vector<unsigned int> a, b;
        for (auto it = expected.begin(i); it != expected.end(i); ++it)
          a.push_back(it->column());
        for (auto it = built.begin(i); it != built.end(i); ++it)
          b.push_back(it->column());
        differing_rows += (a != b);
        with_diagonal +=
          std::find(rows[i].begin(), rows[i].end(), i) != rows[i].end();
        for (const unsigned int j : rows[i])
          missing_lookups +=
            !built.exists(i, j) || built(i, j) != expected(i, j);
      }
    check_range(name + ": compressed", built.is_compressed() ? 1 : 0, 1, 1);
    check_range(name + ": rows whose columns (in order) differ from deal.II's",
                differing_rows,
                0,
                0);
    check_range(name + ": entries, relative to deal.II's",
                double(built.n_nonzero_elements()) /
                  expected.n_nonzero_elements(),
                1.,
                1.);
    check_range(name + ": longest row, relative to deal.II's",
                double(built.max_entries_per_row()) /
                  expected.max_entries_per_row(),
                1.,
                1.);
    check_range(name + ": entries not found or at another index",
                missing_lookups,
                0,
                0);
    if (m == n)
      check_range(name + ": rows given their diagonal (some, not all)",
                  with_diagonal > 0 && with_diagonal < m ? 1 : 0,
                  1,
                  1);

    // The same values on both patterns: the products must agree to the
    // bit (same entries, same order).
    SparseMatrix<double> a(expected), b(built);
    for (unsigned int i = 0; i < m; ++i)
      for (const unsigned int j : rows[i])
        {
          a.set(i, j, 1. + i + 0.001 * j);
          b.set(i, j, 1. + i + 0.001 * j);
        }
    Vector<double> x(n), ya(m), yb(m);
    for (unsigned int j = 0; j < n; ++j)
      x[j] = std::sin(1. + j);
    a.vmult(ya, x);
    b.vmult(yb, x);
    ya -= yb;
    check_range(name + ": |A x - B x|", ya.linfty_norm(), 0., 0.);
  }


  void
  check(const std::string &name, const unsigned int m, const unsigned int n)
  {
    // Rows of random columns, each column once, in random order; every
    // seventh row empty.
    std::mt19937                           random(m + 7 * n);
    std::vector<std::vector<unsigned int>> rows(m);
    for (unsigned int i = 0; i < m; ++i)
      if (i % 7 != 3)
        {
          std::vector<unsigned int> all(n);
          for (unsigned int j = 0; j < n; ++j)
            all[j] = j;
          std::shuffle(all.begin(), all.end(), random);
          all.resize(1 + random() % std::min(n, 40u));
          rows[i] = all;
        }
    SparsityPattern expected;
    expected.copy_from(m, n, rows.begin(), rows.end());
    RowPattern built;
    built.fill(m, n, [&](const unsigned int i, const auto &f) {
      for (const unsigned int j : rows[i])
        f(j);
    });
    compare(name, expected, built, rows);

    // The same rows, each sorted, through fill_ordered(): a square
    // pattern's lengths count its diagonal, given or not.
    std::vector<unsigned int> lengths(m);
    for (unsigned int i = 0; i < m; ++i)
      {
        std::sort(rows[i].begin(), rows[i].end());
        const bool diagonal =
          std::binary_search(rows[i].begin(), rows[i].end(), i);
        lengths[i] = rows[i].size() + (m == n && !diagonal ? 1 : 0);
      }
    RowPattern ordered;
    ordered.fill_ordered(m,
                         n,
                         lengths,
                         [&](const unsigned int i, unsigned int *columns) {
                           for (const unsigned int j : rows[i])
                             if (m != n || j != i)
                               *columns++ = j;
                         });
    compare(name + ", ordered", expected, ordered, rows);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check("square", 500, 500);
  check("rectangular", 300, 90);
  check("one row", 1, 60);
  return exit_code();
}
