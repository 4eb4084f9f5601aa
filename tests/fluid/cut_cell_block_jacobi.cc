// CutCellBlockJacobi, the cut element's smoother preconditioner
// P^-1 = D_F^-1 + sum_K R_K^T W_K (R_K A R_K^T)^-1 W_K R_K, against answers
// known without it:
//
// - blocks that cover disjoint diagonal blocks of a block-diagonal A, the
//   other rows diagonal: P^-1 = A^-1 exactly, so P^-1 A x = x to the
//   single precision of the stored inverses (bound 1e-6 relative);
// - the same block given twice: each unknown is held by two blocks, the
//   weights 1/sqrt(2) on both sides halve each, and the two halves again
//   give A^-1 (a missing or one-sided weight gives 2 A^-1 or sqrt(2) A^-1);
// - overlapping blocks on a symmetric positive definite A (a shifted 1D
//   Laplacian): P^-1 symmetric (|x.P^-1 y - y.P^-1 x| <= 1e-6 |x| |y|
//   |P^-1|) and positive on random vectors;
// - a block whose matrix is indefinite ([1 2; 2 1], eigenvalues 3 and -1)
//   is counted and takes the inverse of its spectral absolute value,
//   [2 -1; -1 2] / 3, so P^-1 (1, 1, 1) = (1/3, 1/3, 1/3) with the
//   diagonal block 3 beside it;
// - over the ranks (1, 2, 3): the shifted 1D Laplacian of 30 rows split
//   among them, overlapping blocks of 4 rows every 3 rows, so that blocks
//   cross the borders of the ranks' rows (each kept by the rank of its
//   smallest row, with the other rows fetched): P^-1 x in double and in
//   float the serial P^-1 x of the whole matrix to 1e-12 (1e-6 in float),
//   and the same number of blocks in all.

#include "../fidus_test.h"

#include <cmath>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/sparse_matrix.h>
#include <fidus/fluid/cut_element/cut_cell_block_jacobi.h>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <random>
#include <string>
#include <vector>

using namespace FidusTest;
using namespace dealii;

namespace
{
  /// The sparse copy of @p dense (its nonzero entries and the diagonal).
  void
  sparse_copy(const FullMatrix<double> &dense,
              SparsityPattern          &pattern,
              SparseMatrix<double>     &matrix)
  {
    const unsigned int     n = dense.m();
    DynamicSparsityPattern dsp(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        if (i == j || dense(i, j) != 0.)
          dsp.add(i, j);
    pattern.copy_from(dsp);
    matrix.reinit(pattern);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        if (dense(i, j) != 0.)
          matrix.set(i, j, dense(i, j));
  }

  Vector<double>
  random_vector(const unsigned int n, std::mt19937 &random)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    Vector<double>                         v(n);
    for (auto &x : v)
      x = u(random);
    return v;
  }

  /// A block-diagonal SPD matrix: blocks of sizes 3, 4 and 2 (random
  /// symmetric, made dominant), then two rows with a diagonal only.
  FullMatrix<double>
  block_diagonal(std::vector<std::vector<unsigned int>> &blocks,
                 std::mt19937                           &random)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    FullMatrix<double>                     a(11, 11);
    unsigned int                           first = 0;
    for (const unsigned int size : {3u, 4u, 2u})
      {
        std::vector<unsigned int> block;
        for (unsigned int p = 0; p < size; ++p)
          {
            block.push_back(first + p);
            for (unsigned int q = 0; q < p; ++q)
              a(first + p, first + q) = a(first + q, first + p) = u(random);
            a(first + p, first + p) = 4. + u(random);
          }
        blocks.push_back(block);
        first += size;
      }
    a(9, 9)   = 2.5;
    a(10, 10) = 0.5;
    return a;
  }

  /// max |P^-1 A x - x| / |x| over a few random x.
  double
  inverse_error(const Fidus::CutCellBlockJacobi &preconditioner,
                const SparseMatrix<double>      &a,
                std::mt19937                    &random)
  {
    double error = 0.;
    for (unsigned int k = 0; k < 3; ++k)
      {
        const Vector<double> x = random_vector(a.m(), random);
        Vector<double>       ax(a.m()), back(a.m());
        a.vmult(ax, x);
        preconditioner.vmult(back, ax);
        back -= x;
        error = std::max(error, back.l2_norm() / x.l2_norm());
      }
    return error;
  }
  /// The blocks across the ranks' rows against the serial blocks.
  void
  over_the_ranks(std::mt19937 &random)
  {
    const MPI_Comm     comm  = MPI_COMM_WORLD;
    const unsigned int n     = 30;
    const unsigned int ranks = Utilities::MPI::n_mpi_processes(comm),
                       rank  = Utilities::MPI::this_mpi_process(comm);
    FullMatrix<double> dense(n, n);
    for (unsigned int i = 0; i < n; ++i)
      {
        dense(i, i) = 2.2;
        if (i + 1 < n)
          dense(i, i + 1) = dense(i + 1, i) = -1.;
      }
    std::vector<std::vector<unsigned int>> blocks;
    for (unsigned int first = 0; first + 4 <= n; first += 3)
      blocks.push_back({first, first + 1, first + 2, first + 3});
    SparsityPattern      pattern;
    SparseMatrix<double> a;
    sparse_copy(dense, pattern, a);
    Fidus::CutCellBlockJacobi serial;
    serial.initialize(a, blocks);

    const unsigned int row_first = n * rank / ranks,
                       row_end   = n * (rank + 1) / ranks;
    const IndexSet owned = Fidus::contiguous_range(row_end - row_first, comm);
    Fidus::DistributedRows<double> rows;
    rows.fill(
      owned,
      owned,
      [&](const unsigned int k, const auto &f) {
        for (auto it = a.begin(row_first + k); it != a.end(row_first + k); ++it)
          f(it->column(), it->value());
      },
      comm);
    Fidus::CutCellBlockJacobi split;
    split.initialize(rows, blocks);
    check_range("over the ranks: blocks summed over the ranks",
                Utilities::MPI::sum(split.n_blocks(), comm),
                blocks.size(),
                blocks.size());

    // The same random x on every rank (the generator's state is).
    const Vector<double> x = random_vector(n, random);
    Vector<double>       px(n);
    serial.vmult(px, x);
    LinearAlgebra::distributed::Vector<double> xd(owned, comm), pd(owned, comm);
    LinearAlgebra::distributed::Vector<float>  xf(owned, comm), pf(owned, comm);
    for (unsigned int k = 0; k < row_end - row_first; ++k)
      {
        xd.local_element(k) = x[row_first + k];
        xf.local_element(k) = x[row_first + k];
      }
    split.vmult(pd, xd);
    split.vmult(pf, xf);
    double error = 0., error_float = 0.;
    for (unsigned int k = 0; k < row_end - row_first; ++k)
      {
        error =
          std::max(error, std::abs(pd.local_element(k) - px[row_first + k]));
        error_float =
          std::max(error_float,
                   std::abs(double(pf.local_element(k)) - px[row_first + k]));
      }
    check_range("over the ranks: |P^-1 x - serial P^-1 x| / |serial P^-1 x|",
                Utilities::MPI::max(error, comm) / px.linfty_norm(),
                0.,
                1e-12);
    check_range("over the ranks, float: |P^-1 x - serial P^-1 x| / "
                "|serial P^-1 x|",
                Utilities::MPI::max(error_float, comm) / px.linfty_norm(),
                0.,
                1e-6);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::mt19937                     random(11);

  {
    std::vector<std::vector<unsigned int>> blocks;
    const FullMatrix<double> dense = block_diagonal(blocks, random);
    SparsityPattern          pattern;
    SparseMatrix<double>     a;
    sparse_copy(dense, pattern, a);
    Fidus::CutCellBlockJacobi p;
    p.initialize(a, blocks);
    check_range("disjoint blocks: |P^-1 A x - x| / |x|",
                inverse_error(p, a, random),
                0.,
                1e-6);
    check_range("disjoint blocks: blocks kept", p.n_blocks(), 3, 3);

    std::vector<std::vector<unsigned int>> twice = blocks;
    twice.insert(twice.end(), blocks.begin(), blocks.end());
    p.initialize(a, twice);
    check_range("every block twice (weights 1/sqrt 2): |P^-1 A x - x| / |x|",
                inverse_error(p, a, random),
                0.,
                1e-6);
  }

  {
    // A shifted 1D Laplacian, blocks {0..3}, {2..5}, {5..8}: rows 2, 3
    // and 5 in two blocks each, row 9 in none.
    const unsigned int n = 10;
    FullMatrix<double> dense(n, n);
    for (unsigned int i = 0; i < n; ++i)
      {
        dense(i, i) = 2.2;
        if (i + 1 < n)
          dense(i, i + 1) = dense(i + 1, i) = -1.;
      }
    SparsityPattern      pattern;
    SparseMatrix<double> a;
    sparse_copy(dense, pattern, a);
    Fidus::CutCellBlockJacobi p;
    p.initialize(a, {{0, 1, 2, 3}, {2, 3, 4, 5}, {5, 6, 7, 8}});
    double asymmetry = 0., smallest = 1e300, largest = 0.;
    for (unsigned int k = 0; k < 5; ++k)
      {
        const Vector<double> x = random_vector(n, random),
                             y = random_vector(n, random);
        Vector<double> px(n), py(n);
        p.vmult(px, x);
        p.vmult(py, y);
        asymmetry =
          std::max(asymmetry,
                   std::abs(x * py - y * px) / (x.l2_norm() * y.l2_norm()));
        smallest = std::min(smallest, (x * px) / (x * x));
        largest  = std::max(largest, px.l2_norm() / x.l2_norm());
      }
    check_range("overlapping blocks: |x.P^-1 y - y.P^-1 x| / (|x| |y| |P^-1|)",
                asymmetry / largest,
                0.,
                1e-6);
    check_range("overlapping blocks: x.P^-1 x / x.x on random x",
                smallest,
                1e-3,
                1e3);
  }

  {
    // Rows 0 and 1: [1 2; 2 1], indefinite; row 2 apart.
    FullMatrix<double> dense(3, 3);
    dense(0, 0) = dense(1, 1) = 1.;
    dense(0, 1) = dense(1, 0) = 2.;
    dense(2, 2)               = 3.;
    SparsityPattern      pattern;
    SparseMatrix<double> a;
    sparse_copy(dense, pattern, a);
    Fidus::CutCellBlockJacobi p;
    p.initialize(a, {{0, 1}, {2}});
    check_range("indefinite block: blocks counted as indefinite",
                p.n_indefinite_blocks(),
                1,
                1);
    check_range("indefinite block: blocks kept", p.n_blocks(), 2, 2);
    Vector<double> e(3), pe(3);
    e = 1.;
    p.vmult(pe, e);
    check_range("indefinite block: |P^-1 1 - (1/3, 1/3, 1/3)|",
                std::abs(pe[0] - 1. / 3.) + std::abs(pe[1] - 1. / 3.) +
                  std::abs(pe[2] - 1. / 3.),
                0.,
                1e-7);
  }

  over_the_ranks(random);
  return exit_code();
}
