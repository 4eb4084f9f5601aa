// galerkin_product (the cut element's multigrid coarse operators): on random
// sparse matrices, C = P^T A P against a dense product of the same matrices,
// entry by entry, to 1e-14 of the largest entry:
// - A square (with its diagonal stored first, as deal.II does) and
//   unsymmetric, P rectangular with empty rows and empty columns (the
//   multigrid's unknowns inside a particle);
// - every entry of the dense product that is not zero is in C's pattern,
//   and every diagonal entry is in it (the multigrid sets a unit diagonal
//   where the product's is zero);
// - C of a symmetric A is symmetric to round-off.

#include "../fidus_test.h"

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <fidus/fluid/cut_element/galerkin_product.h>
#include <random>

using namespace dealii;
using namespace FidusTest;

namespace
{
  /// A random n × m sparse matrix with about @p per_row entries per row;
  /// rows listed in @p empty_rows and columns in @p empty_columns have none.
  /// Symmetric if @p symmetric (n = m).
  void
  random_matrix(const unsigned int               n,
                const unsigned int               m,
                const unsigned int               per_row,
                const std::vector<unsigned int> &empty_rows,
                const std::vector<unsigned int> &empty_columns,
                const bool                       symmetric,
                std::mt19937                    &random,
                SparsityPattern                 &pattern,
                SparseMatrix<double>            &matrix,
                FullMatrix<double>              &dense)
  {
    std::uniform_int_distribution<unsigned int> column(0, m - 1);
    std::uniform_real_distribution<double>      value(-1., 1.);
    const auto listed = [](const std::vector<unsigned int> &list,
                           const unsigned int               k) {
      return std::find(list.begin(), list.end(), k) != list.end();
    };
    dense.reinit(n, m);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int k = 0; k < per_row; ++k)
        {
          const unsigned int j = column(random);
          if (listed(empty_rows, i) || listed(empty_columns, j))
            continue;
          const double v = value(random);
          dense(i, j) += v;
          if (symmetric && i != j)
            dense(j, i) += v;
        }
    DynamicSparsityPattern dsp(n, m);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < m; ++j)
        if (dense(i, j) != 0.)
          dsp.add(i, j);
    pattern.copy_from(dsp);
    matrix.reinit(pattern);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < m; ++j)
        if (dense(i, j) != 0.)
          matrix.set(i, j, dense(i, j));
  }

  void
  check(const std::string &name, const bool symmetric, std::mt19937 &random)
  {
    const unsigned int   n = 300, m = 70;
    SparsityPattern      a_pattern, p_pattern;
    Fidus::RowPattern    c_pattern;
    SparseMatrix<double> a, p, c;
    FullMatrix<double>   a_dense, p_dense;
    random_matrix(n, n, 12, {}, {}, symmetric, random, a_pattern, a, a_dense);
    random_matrix(n,
                  m,
                  4,
                  {5, 17, 299},
                  {0, 33, 69},
                  false,
                  random,
                  p_pattern,
                  p,
                  p_dense);
    Fidus::galerkin_product(a, p, c_pattern, c);

    FullMatrix<double> ap(n, m), expected(m, m);
    a_dense.mmult(ap, p_dense);
    p_dense.Tmmult(expected, ap);
    double largest = 0.;
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        largest = std::max(largest, std::abs(expected(i, j)));
    double       error = 0., asymmetry = 0.;
    unsigned int missing = 0, diagonals = 0;
    for (unsigned int i = 0; i < m; ++i)
      {
        diagonals += c_pattern.exists(i, i) ? 1 : 0;
        for (unsigned int j = 0; j < m; ++j)
          {
            const bool stored = c_pattern.exists(i, j);
            if (!stored && expected(i, j) != 0.)
              ++missing;
            const double value = stored ? c.el(i, j) : 0.;
            error     = std::max(error, std::abs(value - expected(i, j)));
            asymmetry = std::max(asymmetry, std::abs(value - c.el(j, i)));
          }
      }
    check_range(name + ": max |C - P^T A P| / max |P^T A P|",
                error / largest,
                0.,
                1e-14);
    check_range(name + ": nonzero entries of P^T A P missing from C",
                missing,
                0.,
                0.);
    check_range(name + ": diagonal entries in C's pattern", diagonals, m, m);
    check_range(name + ": C's size", c.m() == m && c.n() == m ? 1 : 0, 1, 1);
    if (symmetric)
      check_range(name + ": max |C - C^T| / max |C|",
                  asymmetry / largest,
                  0.,
                  1e-14);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::mt19937                     random(5);
  check("unsymmetric A", false, random);
  check("symmetric A", true, random);
  return exit_code();
}
