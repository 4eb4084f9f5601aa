#include <algorithm>
#include <cmath>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <fidus/fluid/cut_element/component_coupling.h>
#include <fidus/fluid/cut_element/cut_cell_block_jacobi.h>
#include <limits>
#include <type_traits>

namespace Fidus
{
  namespace
  {
    /// @p a becomes the inverse of its spectral absolute value,
    /// Q |Lambda|^-1 Q^T (eigenvalues below 1e-12 of the largest in
    /// magnitude are left out).
    void
    absolute_inverse(LAPACKFullMatrix<double> &a)
    {
      const unsigned int       n = a.m();
      LAPACKFullMatrix<double> l(a);
      Vector<double>           eigenvalues;
      FullMatrix<double>       q;
      l.compute_eigenvalues_symmetric(-std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::max(),
                                      0.,
                                      eigenvalues,
                                      q);
      double largest = 0.;
      for (const double e : eigenvalues)
        largest = std::max(largest, std::abs(e));
      a.reinit(n, n);
      for (unsigned int k = 0; k < eigenvalues.size(); ++k)
        if (std::abs(eigenvalues[k]) > 1e-12 * largest)
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              a(i, j) += q(i, k) * q(j, k) / std::abs(eigenvalues[k]);
    }



    /**
     * The rows @p others of @p a (global indices that other ranks own,
     * ascending), fetched from their owners, f(row, columns, values, n) as
     * DistributedRows::for_rows_of_others() gives them; each owner sends
     * of a row only the columns that one of @p blocks (every rank's) shares
     * with it. Collective.
     */
    void
    fetch_block_rows(const DistributedRows<double>                &a,
                     const std::vector<std::vector<unsigned int>> &blocks,
                     const std::vector<types::global_dof_index>   &others,
                     const std::function<void(types::global_dof_index,
                                              const types::global_dof_index *,
                                              const double *,
                                              std::size_t)>       &f)
    {
      using Index = types::global_dof_index;
      // Which blocks hold each row (CSR over the global rows; every rank has
      // the list), so that an owner sends of a row only the columns a block
      // shares with it.
      std::vector<std::size_t>  row_start(a.m() + 1, 0);
      std::vector<unsigned int> block_of;
      for (const auto &block : blocks)
        for (const unsigned int g : block)
          ++row_start[g + 1];
      for (unsigned int i = 0; i < a.m(); ++i)
        row_start[i + 1] += row_start[i];
      block_of.resize(row_start[a.m()]);
      {
        std::vector<std::size_t> at(row_start.begin(), row_start.end() - 1);
        for (unsigned int b = 0; b < blocks.size(); ++b)
          for (const unsigned int g : blocks[b])
            block_of[at[g]++] = b;
      }
      const auto share_a_block = [&](const Index i, const Index j) {
        for (std::size_t e = row_start[i]; e < row_start[i + 1]; ++e)
          {
            const auto &block = blocks[block_of[e]];
            if (std::find(block.begin(), block.end(), j) != block.end())
              return true;
          }
        return false;
      };
      a.for_rows_of_others(others, f, share_a_block);
    }
  } // namespace



  void
  CutCellBlockJacobi::initialize(
    const SparseMatrix<double>                   &a,
    const std::vector<std::vector<unsigned int>> &blocks,
    const std::vector<unsigned char>             &component)
  {
    exchange = false;
    block_rows.reset();
    std::vector<double> diagonal(a.m());
    for (unsigned int i = 0; i < a.m(); ++i)
      diagonal[i] = a.diag_element(i);
    setup(
      diagonal,
      [&](const unsigned int                               i,
          const std::function<void(unsigned int, double)> &f) {
        for (auto it = a.begin(i); it != a.end(i); ++it)
          if (couples_within_component(component, i, it->column()))
            f(it->column(), it->value());
      },
      blocks,
      a.m());
  }



  void
  CutCellBlockJacobi::initialize(
    const DistributedRows<double>                &a,
    const std::vector<std::vector<unsigned int>> &blocks,
    const std::vector<unsigned char>             &component)
  {
    using Index              = types::global_dof_index;
    const unsigned int n     = a.local_rows();
    const Index        first = a.first_row();
    const auto         owned = [&](const Index g) {
      return g >= first && g < first + n;
    };
    // This rank's blocks: those whose smallest row it owns; the other
    // ranks' rows they hold.
    std::vector<const std::vector<unsigned int> *> mine;
    std::vector<Index>                             others;
    for (const auto &block : blocks)
      if (!block.empty() &&
          owned(*std::min_element(block.begin(), block.end())))
        {
          mine.push_back(&block);
          for (const unsigned int g : block)
            if (!owned(g))
              others.push_back(g);
        }
    std::sort(others.begin(), others.end());
    others.erase(std::unique(others.begin(), others.end()), others.end());
    IndexSet ghosts(a.m());
    ghosts.add_indices(others.begin(), others.end());
    const MPI_Comm comm = a.get_mpi_communicator();
    block_rows          = std::make_shared<const Utilities::MPI::Partitioner>(
      a.locally_owned_rows(),
      ghosts,
      comm);
    exchange = Utilities::MPI::max(others.empty() ? 0 : 1, comm) > 0;
    const unsigned int n_rows = n + others.size();
    const auto         local  = [&](const Index g) -> unsigned int {
      return owned(g)                      ? g - first :
                      block_rows->is_ghost_entry(g) ? block_rows->global_to_local(g) :
                                                      n_rows;
    };

    // The other ranks' rows, in local numbering (only where some rank's
    // blocks hold another's rows: the exchange is collective).
    std::vector<std::vector<std::pair<unsigned int, double>>> fetched(
      others.size());
    if (exchange)
      fetch_block_rows(
        a,
        blocks,
        others,
        [&](const Index       g,
            const Index      *columns,
            const double     *values,
            const std::size_t length) {
          auto &row = fetched[local(g) - n];
          for (std::size_t e = 0; e < length; ++e)
            if (local(columns[e]) < n_rows &&
                (component.empty() ||
                 couples_within_component(component, g, columns[e])))
              row.emplace_back(local(columns[e]), values[e]);
        });
    // The weights count every rank's blocks (each rank has the list).
    std::vector<unsigned int> count(n_rows, 0);
    for (const auto &block : blocks)
      for (const unsigned int g : block)
        if (local(g) < n_rows)
          ++count[local(g)];
    std::vector<std::vector<unsigned int>> local_blocks;
    for (const auto *block : mine)
      {
        local_blocks.emplace_back();
        for (const unsigned int g : *block)
          local_blocks.back().push_back(local(g));
      }

    std::vector<double> diagonal(n);
    for (unsigned int k = 0; k < n; ++k)
      diagonal[k] = a.diag_element(k);
    const auto &columns = a.column_partitioner();
    setup(
      diagonal,
      [&](const unsigned int                               k,
          const std::function<void(unsigned int, double)> &f) {
        if (k >= n)
          {
            for (const auto &entry : fetched[k - n])
              f(entry.first, entry.second);
            return;
          }
        a.for_row(k, [&](const unsigned int j, const double v) {
          const Index g = columns.local_to_global(j);
          if (component.empty() ||
              couples_within_component(component, first + k, g))
            f(local(g), v);
        });
      },
      local_blocks,
      n_rows,
      count);
  }



  void
  CutCellBlockJacobi::setup(
    const std::vector<double> &diagonal,
    const std::function<void(unsigned int,
                             const std::function<void(unsigned int, double)> &)>
                                                 &row,
    const std::vector<std::vector<unsigned int>> &blocks,
    const unsigned int                            n_rows,
    const std::vector<unsigned int>              &block_count)
  {
    const unsigned int n = diagonal.size();
    block_start.assign(1, 0);
    rows.clear();
    inverse_start.assign(1, 0);
    inverses.clear();
    n_indefinite = 0;

    // The blocks' inverses, unweighted. The Nitsche terms make the whole
    // system positive definite with the ghost penalties' help from the
    // neighbours, not every cell's part of it: a cell whose fluid is a
    // sliver can have an indefinite block (8 of 108 in a 2D pair at
    // a/h = 6.4). Such a block gets the inverse of its spectral absolute
    // value, Q |Lambda|^-1 Q^T, which keeps P^-1 positive definite and acts
    // as the inverse on the block's positive modes (leaving the block out
    // cost 8 of 43 FGMRES iterations there).
    std::vector<int>         position(n_rows, -1);
    LAPACKFullMatrix<double> block_matrix, copy;
    for (const auto &block : blocks)
      {
        const unsigned int m = block.size();
        for (unsigned int p = 0; p < m; ++p)
          position[block[p]] = p;
        block_matrix.reinit(m, m);
        for (unsigned int p = 0; p < m; ++p)
          row(block[p], [&](const unsigned int j, const double v) {
            if (j < n_rows && position[j] >= 0)
              block_matrix(p, position[j]) = v;
          });
        for (unsigned int p = 0; p < m; ++p)
          position[block[p]] = -1;
        // The inverse from the Cholesky factor (LAPACK's potrf and potri),
        // which fails exactly where the block is not positive definite.
        copy = block_matrix;
        block_matrix.set_property(LAPACKSupport::symmetric);
        try
          {
            block_matrix.compute_cholesky_factorization();
            block_matrix.invert();
          }
        catch (const dealii::ExceptionBase &)
          {
            ++n_indefinite;
            block_matrix = copy;
            absolute_inverse(block_matrix);
          }
        rows.insert(rows.end(), block.begin(), block.end());
        block_start.push_back(rows.size());
        for (unsigned int p = 0; p < m; ++p)
          for (unsigned int q = p; q < m; ++q)
            inverses.push_back(static_cast<float>(block_matrix(p, q)));
        inverse_start.push_back(inverses.size());
      }

    // The weights: 1/sqrt(the number of blocks that hold an unknown) on
    // both sides; point Jacobi where none does.
    std::vector<unsigned int> count = block_count;
    if (count.empty())
      {
        count.assign(n_rows, 0);
        for (const unsigned int i : rows)
          ++count[i];
      }
    inverse_diagonal.reinit(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        const double d      = diagonal[i];
        inverse_diagonal[i] = count[i] > 0 ? 0. : d > 0. ? 1. / d : 1.;
      }
    for (unsigned int b = 0; b < n_blocks(); ++b)
      {
        const unsigned int *const r       = rows.data() + block_start[b];
        const unsigned int        m       = block_start[b + 1] - block_start[b];
        float                    *inverse = inverses.data() + inverse_start[b];
        for (unsigned int p = 0; p < m; ++p)
          for (unsigned int q = p; q < m; ++q)
            *inverse++ /= std::sqrt(double(count[r[p]]) * count[r[q]]);
      }
  }



  template <typename Number>
  void
  CutCellBlockJacobi::add_blocks(const Number *in, Number *out) const
  {
    for (unsigned int b = 0; b < n_blocks(); ++b)
      {
        const unsigned int *const r = rows.data() + block_start[b];
        const unsigned int        m = block_start[b + 1] - block_start[b];
        x.resize(m);
        y.assign(m, 0.);
        for (unsigned int p = 0; p < m; ++p)
          x[p] = in[r[p]];
        // y = B x from B's upper triangle: row p gives y_p its part on and
        // right of the diagonal, and by symmetry x_p times the row to the
        // y_q with q > p.
        const float *entry = inverses.data() + inverse_start[b];
        for (unsigned int p = 0; p < m; ++p)
          {
            const double xp  = x[p];
            double       sum = entry[0] * xp;
            for (unsigned int q = p + 1; q < m; ++q)
              {
                sum += entry[q - p] * x[q];
                y[q] += entry[q - p] * xp;
              }
            y[p] += sum;
            entry += m - p;
          }
        for (unsigned int p = 0; p < m; ++p)
          out[r[p]] += y[p];
      }
  }



  template <typename Number>
  void
  CutCellBlockJacobi::vmult_exchanging(
    LinearAlgebra::distributed::Vector<Number>       &dst,
    const LinearAlgebra::distributed::Vector<Number> &src,
    LinearAlgebra::distributed::Vector<Number>       &in,
    LinearAlgebra::distributed::Vector<Number>       &out) const
  {
    if (in.get_partitioner() != block_rows)
      {
        in.reinit(block_rows);
        out.reinit(block_rows);
      }
    const unsigned int n = inverse_diagonal.size();
    std::copy(src.begin(), src.begin() + n, in.begin());
    in.update_ghost_values();
    std::fill(out.get_values(),
              out.get_values() + n + block_rows->n_ghost_indices(),
              Number());
    add_blocks(in.get_values(), out.get_values());
    // The other ranks' rows' results to their owners, added there.
    out.compress(VectorOperation::add);
    for (unsigned int i = 0; i < n; ++i)
      dst.local_element(i) =
        src.local_element(i) * inverse_diagonal[i] + out.local_element(i);
  }



  template <typename VectorType>
  void
  CutCellBlockJacobi::vmult(VectorType &dst, const VectorType &src) const
  {
    if constexpr (std::is_same_v<VectorType,
                                 LinearAlgebra::distributed::Vector<double>>)
      {
        if (exchange)
          return vmult_exchanging(dst, src, in_double, out_double);
      }
    if constexpr (std::is_same_v<VectorType,
                                 LinearAlgebra::distributed::Vector<float>>)
      {
        if (exchange)
          return vmult_exchanging(dst, src, in_float, out_float);
      }
    auto       *out = dst.begin();
    const auto *in  = src.begin();
    for (unsigned int i = 0; i < inverse_diagonal.size(); ++i)
      out[i] = in[i] * inverse_diagonal[i];
    add_blocks(in, out);
  }

  template void
  CutCellBlockJacobi::vmult(Vector<double> &, const Vector<double> &) const;
  template void
  CutCellBlockJacobi::vmult(Vector<float> &, const Vector<float> &) const;
  template void
  CutCellBlockJacobi::vmult(
    LinearAlgebra::distributed::Vector<double> &,
    const LinearAlgebra::distributed::Vector<double> &) const;
  template void
  CutCellBlockJacobi::vmult(
    LinearAlgebra::distributed::Vector<float> &,
    const LinearAlgebra::distributed::Vector<float> &) const;
} // namespace Fidus
