// DistributedRows and distributed_galerkin_product (the cut element's
// matrices over MPI ranks) against the serial SparseMatrix products and a
// dense P^T A P of the same random matrices, held whole on every rank. The
// rows are split unevenly (one rank owns no coarse row on 3 ranks), the
// matrices couple every pair of ranks, and P has empty rows and columns
// (the multigrid's unknowns inside a particle). Checked on 1, 2 and 3
// ranks:
// - A x, A^T x, P x, P^T x (rectangular P) to 1e-14 of the largest entry
//   of the serial result, and A x in float (copied from double) to 1e-6;
// - the same for A's rows read in place from the SparseMatrix (borrow()),
//   with its diagonal exactly;
// - P^T A P: every entry to 1e-14 of the largest entry of the dense
//   product, its entries exactly the positions the patterns give (the
//   boolean product of P^T, A and P) and every diagonal entry, first in its
//   row (the multigrid sets a unit diagonal where the product's is zero),
//   for a symmetric and an unsymmetric A, and with A read without the
//   couplings between components (component = i mod 3, some rows rigid);
// - P^T x of a P large enough (200 000 rows) for the transposed product
//   to scatter several row ranges into buffers of their own: to 1e-14 of
//   the serial product, and the same to the bit on one thread and on two.

#include "../fidus_test.h"

#include <deal.II/base/multithread_info.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>
#include <fidus/fluid/cut_element/distributed_galerkin_product.h>
#include <map>
#include <random>

using namespace dealii;
using namespace FidusTest;
using Fidus::DistributedRows;

namespace
{
  /// A random n × m sparse matrix with about @p per_row entries per row
  /// (symmetric if asked), the same on every rank; the rows in
  /// @p empty_rows and the columns in @p empty_columns have none.
  void
  random_matrix(const unsigned int               n,
                const unsigned int               m,
                const unsigned int               per_row,
                const bool                       symmetric,
                std::mt19937                    &random,
                SparsityPattern                 &pattern,
                SparseMatrix<double>            &matrix,
                const std::vector<unsigned int> &empty_rows    = {},
                const std::vector<unsigned int> &empty_columns = {})
  {
    std::uniform_int_distribution<unsigned int> column(0, m - 1);
    std::uniform_real_distribution<double>      value(-1., 1.);
    std::vector<std::map<unsigned int, double>> rows(n);
    const auto listed = [](const std::vector<unsigned int> &list,
                           const unsigned int               k) {
      return std::find(list.begin(), list.end(), k) != list.end();
    };
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int k = 0; k < per_row; ++k)
        {
          const unsigned int j = column(random);
          const double       v = value(random);
          if (listed(empty_rows, i) || listed(empty_columns, j))
            continue;
          rows[i][j] += v;
          if (symmetric && i != j)
            rows[j][i] += v;
        }
    DynamicSparsityPattern dsp(n, m);
    for (unsigned int i = 0; i < n; ++i)
      for (const auto &e : rows[i])
        dsp.add(i, e.first);
    pattern.copy_from(dsp);
    matrix.reinit(pattern);
    for (unsigned int i = 0; i < n; ++i)
      for (const auto &e : rows[i])
        matrix.set(i, e.first, e.second);
  }

  /// This rank's share of @p n indices: rank r of R gets a share growing
  /// with r (the last rank none when @p last_empty).
  IndexSet
  uneven_range(const unsigned int n, const bool last_empty)
  {
    const unsigned int ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const unsigned int rank  = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    const unsigned int used  = last_empty && ranks > 1 ? ranks - 1 : ranks;
    unsigned int       weight = 0, before = 0;
    for (unsigned int r = 0; r < used; ++r)
      {
        weight += r + 1;
        if (r < rank)
          before += r + 1;
      }
    const unsigned int first = std::size_t(n) * before / weight;
    const unsigned int last =
      rank < used ? std::size_t(n) * (before + rank + 1) / weight : n;
    return Fidus::contiguous_range(rank < used ? last - first : 0,
                                   MPI_COMM_WORLD);
  }

  /// The owned rows of @p m as a DistributedRows.
  void
  distribute(const SparseMatrix<double> &m,
             const IndexSet             &rows,
             const IndexSet             &columns,
             DistributedRows<double>    &out)
  {
    std::vector<std::size_t>             start{0};
    std::vector<types::global_dof_index> cols;
    std::vector<double>                  values;
    for (const auto i : rows)
      {
        for (auto e = m.begin(i); e != m.end(i); ++e)
          {
            cols.push_back(e->column());
            values.push_back(e->value());
          }
        start.push_back(cols.size());
      }
    out.reinit(rows, columns, start, cols, values, MPI_COMM_WORLD);
  }

  template <typename Number>
  LinearAlgebra::distributed::Vector<Number>
  distributed(const Vector<double> &x, const IndexSet &owned)
  {
    LinearAlgebra::distributed::Vector<Number> v(owned, MPI_COMM_WORLD);
    for (const auto i : owned)
      v[i] = x[i];
    return v;
  }

  /// max over the owned entries of |y - expected| / max |expected|, over
  /// all ranks.
  template <typename Number>
  double
  error(const LinearAlgebra::distributed::Vector<Number> &y,
        const Vector<double>                             &expected)
  {
    double e = 0.;
    for (const auto i : y.locally_owned_elements())
      e = std::max(e, std::abs(double(y[i]) - expected[i]));
    return Utilities::MPI::max(e, MPI_COMM_WORLD) / expected.linfty_norm();
  }

  /**
   * The reference: C = P^T A P formed densely, A read without its entries
   * (i, j) between different components (component[i] != component[j],
   * neither 255, when @p component is given), and where C has entries:
   * the positions the boolean product of the patterns gives, and every
   * diagonal.
   */
  void
  dense_galerkin_product(const SparseMatrix<double>       &a,
                         const SparseMatrix<double>       &p,
                         const std::vector<unsigned char> &component,
                         FullMatrix<double>               &c,
                         std::vector<std::vector<bool>>   &stored)
  {
    const unsigned int             n = a.m(), m = p.n();
    FullMatrix<double>             ap(n, m);
    std::vector<std::vector<bool>> ap_stored(n, std::vector<bool>(m, false));
    for (unsigned int i = 0; i < n; ++i)
      for (auto e = a.begin(i); e != a.end(i); ++e)
        {
          const unsigned int j = e->column();
          if (!component.empty() && component[i] != component[j] &&
              component[i] != 255 && component[j] != 255)
            continue;
          for (auto f = p.begin(j); f != p.end(j); ++f)
            {
              ap(i, f->column()) += e->value() * f->value();
              ap_stored[i][f->column()] = true;
            }
        }
    c.reinit(m, m);
    stored.assign(m, std::vector<bool>(m, false));
    for (unsigned int i = 0; i < n; ++i)
      for (auto f = p.begin(i); f != p.end(i); ++f)
        for (unsigned int l = 0; l < m; ++l)
          if (ap_stored[i][l])
            {
              c(f->column(), l) += f->value() * ap(i, l);
              stored[f->column()][l] = true;
            }
    for (unsigned int k = 0; k < m; ++k)
      stored[k][k] = true;
  }

  void
  check(const std::string &name, const bool symmetric, std::mt19937 &random)
  {
    const unsigned int   n = 300, m = 70;
    SparsityPattern      a_pattern, p_pattern;
    SparseMatrix<double> a, p;
    random_matrix(n, n, 12, symmetric, random, a_pattern, a);
    random_matrix(n,
                  m,
                  4,
                  false,
                  random,
                  p_pattern,
                  p,
                  {5, 17, 299},
                  {0, 33, 69});
    const IndexSet          fine   = uneven_range(n, false);
    const IndexSet          coarse = uneven_range(m, true);
    DistributedRows<double> a_rows, p_rows;
    distribute(a, fine, fine, a_rows);
    distribute(p, fine, coarse, p_rows);

    Vector<double>                         x(n), xc(m), y(n), yc(m);
    std::uniform_real_distribution<double> value(-1., 1.);
    for (auto &v : x)
      v = value(random);
    for (auto &v : xc)
      v = value(random);
    LinearAlgebra::distributed::Vector<double> dy(fine, MPI_COMM_WORLD),
      dyc(coarse, MPI_COMM_WORLD);
    a.vmult(y, x);
    a_rows.vmult(dy, distributed<double>(x, fine));
    check_range(name + ": A x", error(dy, y), 0., 1e-14);
    a.Tvmult(y, x);
    a_rows.Tvmult(dy, distributed<double>(x, fine));
    check_range(name + ": A^T x", error(dy, y), 0., 1e-14);
    p.vmult(y, xc);
    p_rows.vmult(dy, distributed<double>(xc, coarse));
    check_range(name + ": P x", error(dy, y), 0., 1e-14);
    p.Tvmult(yc, x);
    p_rows.Tvmult(dyc, distributed<double>(x, fine));
    check_range(name + ": P^T x", error(dyc, yc), 0., 1e-14);
    DistributedRows<float> a_float;
    a_float.copy_from(a_rows);
    LinearAlgebra::distributed::Vector<float> fy(fine, MPI_COMM_WORLD);
    a_float.vmult(fy, distributed<float>(x, fine));
    a.vmult(y, x);
    check_range(name + ": A x in float", error(fy, y), 0., 1e-6);

    // A's rows read in place (borrow()): the same products, diagonal and
    // float copy.
    DistributedRows<double> a_borrowed;
    a_borrowed.borrow(fine, a, MPI_COMM_WORLD);
    a.vmult(y, x);
    a_borrowed.vmult(dy, distributed<double>(x, fine));
    check_range(name + ": A x, borrowed", error(dy, y), 0., 1e-14);
    a.Tvmult(y, x);
    a_borrowed.Tvmult(dy, distributed<double>(x, fine));
    check_range(name + ": A^T x, borrowed", error(dy, y), 0., 1e-14);
    double diagonal = 0.;
    for (unsigned int k = 0; k < a_borrowed.local_rows(); ++k)
      diagonal = std::max(diagonal,
                          std::abs(a_borrowed.diag_element(k) -
                                   a.diag_element(a_borrowed.first_row() + k)));
    check_range(name + ": diagonal, borrowed",
                Utilities::MPI::max(diagonal, MPI_COMM_WORLD),
                0.,
                0.);
    a_float.copy_from(a_borrowed);
    a_float.vmult(fy, distributed<float>(x, fine));
    a.vmult(y, x);
    check_range(name + ": A x in float, from the borrowed rows",
                error(fy, y),
                0.,
                1e-6);

    for (const bool separate : {false, true})
      {
        std::vector<unsigned char> component;
        if (separate)
          for (unsigned int i = 0; i < n; ++i)
            component.push_back(i % 17 == 0 ? 255 : i % 3);
        FullMatrix<double>             c;
        std::vector<std::vector<bool>> stored;
        dense_galerkin_product(a, p, component, c, stored);
        DistributedRows<double> c_rows;
        Fidus::distributed_galerkin_product(a_rows,
                                            p_rows,
                                            coarse,
                                            c_rows,
                                            component);
        double       largest = 0., e = 0.;
        unsigned int expected_entries = 0;
        for (unsigned int i = 0; i < m; ++i)
          for (unsigned int j = 0; j < m; ++j)
            {
              largest = std::max(largest, std::abs(c(i, j)));
              expected_entries += stored[i][j] ? 1 : 0;
            }
        unsigned int extra = 0, not_first = 0;
        for (unsigned int k = 0; k < c_rows.local_rows(); ++k)
          {
            const unsigned int i = c_rows.first_row() + k;
            c_rows.for_row(k, [&](const unsigned int j, const double v) {
              const auto g = c_rows.column_partitioner().local_to_global(j);
              if (!stored[i][g])
                ++extra;
              e = std::max(e, std::abs(v - c(i, g)));
            });
            // The diagonal first in every row.
            bool first_entry = true;
            c_rows.for_row(k, [&](const unsigned int j, const double) {
              if (first_entry &&
                  c_rows.column_partitioner().local_to_global(j) != i)
                ++not_first;
              first_entry = false;
            });
          }
        const std::string what =
          name + (separate ? ", components apart" : "") + ": ";
        check_range(what + "max |C - C_dense| / max |C_dense|",
                    Utilities::MPI::max(e, MPI_COMM_WORLD) / largest,
                    0.,
                    1e-14);
        check_range(what + "entries where the patterns give none",
                    Utilities::MPI::sum(extra, MPI_COMM_WORLD),
                    0.,
                    0.);
        check_range(what + "rows whose diagonal is not first",
                    Utilities::MPI::sum(not_first, MPI_COMM_WORLD),
                    0.,
                    0.);
        const double total =
          Utilities::MPI::sum(double(c_rows.n_local_entries()), MPI_COMM_WORLD);
        check_range(what + "entries, against those the patterns give",
                    total - double(expected_entries),
                    0.,
                    0.);
        check_range(what + "size", c_rows.m() == m ? 1 : 0, 1, 1);
      }
  }

  /// P^T x with P's rows in several ranges per rank (see the header).
  void
  check_large_transposed(std::mt19937 &random)
  {
    const unsigned int   n = 200000, m = 30000;
    SparsityPattern      pattern;
    SparseMatrix<double> p;
    random_matrix(n, m, 6, false, random, pattern, p);
    const IndexSet          fine   = uneven_range(n, false);
    const IndexSet          coarse = uneven_range(m, true);
    DistributedRows<double> p_rows;
    distribute(p, fine, coarse, p_rows);
    Vector<double>                         x(n), y(m);
    std::uniform_real_distribution<double> value(-1., 1.);
    for (auto &v : x)
      v = value(random);
    p.Tvmult(y, x);
    LinearAlgebra::distributed::Vector<double> one(coarse, MPI_COMM_WORLD),
      two(one);
    MultithreadInfo::set_thread_limit(1);
    p_rows.Tvmult(one, distributed<double>(x, fine));
    MultithreadInfo::set_thread_limit(2);
    p_rows.Tvmult(two, distributed<double>(x, fine));
    check_range("large P^T x", error(two, y), 0., 1e-14);
    two -= one;
    check_range("large P^T x, on two threads against one",
                two.linfty_norm(),
                0.,
                0.);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::mt19937                     random(11);
  check("unsymmetric A", false, random);
  check("symmetric A", true, random);
  check_large_transposed(random);
  return exit_code();
}
