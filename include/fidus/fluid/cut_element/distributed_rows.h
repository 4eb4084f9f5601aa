#ifndef fidus_fluid_cut_element_distributed_rows_h
#define fidus_fluid_cut_element_distributed_rows_h

#include <algorithm>
#include <cstddef>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/subscriptor.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/sparse_matrix.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * A sparse matrix whose rows are split among the MPI ranks of a
   * communicator in contiguous ranges, in float or double: the storage of
   * the cut element's iterative solve on more than one rank
   * (doc/developer/architecture.md, "The cut element over ranks").
   *
   * Each rank holds its own rows, compressed, with local column numbers:
   * first the columns it owns in the column space, in order, then the
   * others ("ghost" columns) in ascending global order, as deal.II's
   * Utilities::MPI::Partitioner numbers them. A product imports the ghost
   * columns' values from their owners into a buffer of the matrix's own,
   * so the vectors it takes (LinearAlgebra::distributed::Vector over the
   * row or column space) need no ghost entries, and one vector serves
   * matrices with different ghost columns. When no rank has a ghost
   * column (one rank, or blocks that do not couple the ranks) nothing is
   * communicated.
   *
   * A square matrix (the row and the column space the same, split alike)
   * keeps each row's diagonal first, as deal.II's SparseMatrix does, so
   * that its diagonal is read in one step. (A Subscriptor, as deal.II's
   * Chebyshev smoother holds its matrix through a SmartPointer.)
   */
  template <typename Number>
  class DistributedRows : public Subscriptor
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<Number>;

    /**
     * Become the matrix whose rows owned here are @p owned_rows (a
     * contiguous range; the ranks' ranges tile the row space in the order
     * of the ranks), with columns in a space of which this rank owns
     * @p owned_columns (likewise). Local row k (global index first + k)
     * has the global columns @p columns[start[k]] to
     * @p columns[start[k + 1] - 1], each at most once, in any order, with
     * @p values. A square matrix gets every diagonal entry (zero where
     * absent). Collective on @p comm.
     */
    void
    reinit(const IndexSet                             &owned_rows,
           const IndexSet                             &owned_columns,
           const std::vector<std::size_t>             &start,
           const std::vector<types::global_dof_index> &columns,
           const std::vector<double>                  &values,
           const MPI_Comm                              comm);

    /**
     * reinit() from a function instead of arrays: @p row(k, f) calls
     * f(global column, value) for each entry of local row k (each column
     * at most once, in the order they are to be stored). It is called
     * twice per row, from the threads (MultithreadInfo::n_threads()), and
     * nothing but the matrix is allocated: the multigrid's finest level is
     * copied from the velocity block this way, in float, without a double
     * copy in between.
     */
    template <typename Row>
    void
    fill(const IndexSet &owned_rows,
         const IndexSet &owned_columns,
         const Row      &row,
         const MPI_Comm  comm);

    /**
     * Become the rows @p owned_rows of the square @p matrix (its rows
     * numbered as this matrix's global rows, the columns split as the
     * rows), reading its values in place: only the local column numbers
     * are stored here. The rows of @p matrix outside @p owned_rows are not
     * read; @p matrix must outlive this object and keep its pattern and
     * values. Number must be double. Collective on @p comm.
     */
    void
    borrow(const IndexSet             &owned_rows,
           const SparseMatrix<double> &matrix,
           const MPI_Comm              comm);

    /// The same structure as @p other, its values converted to Number.
    template <typename OtherNumber>
    void
    copy_from(const DistributedRows<OtherNumber> &other);

    /// Global numbers of rows and columns.
    types::global_dof_index
    m() const
    {
      return owned_rows.size();
    }
    types::global_dof_index
    n() const
    {
      return partitioner ? partitioner->size() : 0;
    }

    /// The rows owned here, and their number.
    const IndexSet &
    locally_owned_rows() const
    {
      return owned_rows;
    }
    unsigned int
    local_rows() const
    {
      return row_start.size() - 1;
    }

    /// Global index of local row 0 (of the range owned here).
    types::global_dof_index
    first_row() const
    {
      return first;
    }

    /// The column space: the columns owned here and the ghost columns.
    const Utilities::MPI::Partitioner &
    column_partitioner() const
    {
      return *partitioner;
    }

    MPI_Comm
    get_mpi_communicator() const
    {
      return communicator;
    }

    /// f(local column, value) for each entry of local row @p k, in storage
    /// order (the diagonal first in a square matrix).
    template <typename F>
    void
    for_row(const unsigned int k, const F &f) const
    {
      for (std::size_t e = row_start[k]; e < row_start[k + 1]; ++e)
        f(column[e], values()[e]);
    }

    /// The number of entries of local row @p k.
    unsigned int
    row_length(const unsigned int k) const
    {
      return row_start[k + 1] - row_start[k];
    }

    /// The diagonal entry of local row @p k of a square matrix.
    /// (With borrow(), the borrowed matrix's entry.)
    Number &
    diag_element(const unsigned int k)
    {
      return const_cast<Number &>(values()[row_start[k]]);
    }
    Number
    diag_element(const unsigned int k) const
    {
      return values()[row_start[k]];
    }

    /// Entries stored on this rank.
    std::size_t
    n_local_entries() const
    {
      return row_start.back();
    }

    /// dst = A src (dst over the row space, src over the column space).
    void
    vmult(VectorType &dst, const VectorType &src) const;

    /// dst += A src.
    void
    vmult_add(VectorType &dst, const VectorType &src) const;

    /// dst = A^T src (dst over the column space, src over the row space).
    void
    Tvmult(VectorType &dst, const VectorType &src) const;

    /// dst += A^T src.
    void
    Tvmult_add(VectorType &dst, const VectorType &src) const;

    /**
     * f(global row, global columns, values, number of entries) for each
     * of @p rows, global indices of rows that other ranks own (ascending),
     * fetched from their owners; with @p keep, only the entries (row,
     * column) for which the owner's keep(row, column) is true are sent.
     * Collective: every rank calls it, each with its own list (which may
     * be empty).
     */
    void
    for_rows_of_others(
      const std::vector<types::global_dof_index>         &rows,
      const std::function<void(types::global_dof_index,
                               const types::global_dof_index *,
                               const double *,
                               std::size_t)>             &f,
      const std::function<bool(types::global_dof_index,
                               types::global_dof_index)> &keep = {}) const;

    /// Bytes held on this rank.
    std::size_t
    memory_consumption() const;

  private:
    /// The part of fill() and reinit() that does not depend on the rows:
    /// the ranges, the column partitioner from this rank's @p ghosts
    /// (sorted, distinct) and the import buffer. Collective.
    void
    setup_columns(const IndexSet                             &rows,
                  const IndexSet                             &owned_columns,
                  const std::vector<types::global_dof_index> &ghosts,
                  const MPI_Comm                              comm);

    /// The local number of the global column @p g.
    unsigned int
    local_column(const types::global_dof_index g) const
    {
      return g >= column_first && g < column_end ?
               g - column_first :
               partitioner->global_to_local(g);
    }

    /// dst = A src, or dst += A src with @p add.
    void
    multiply(VectorType &dst, const VectorType &src, const bool add) const;

    /// The values src imports (owned ones first, then the ghost columns);
    /// @p src's own array if nothing is imported.
    const Number *
    imported(const VectorType &src) const;

    template <typename>
    friend class DistributedRows;

    MPI_Comm                communicator;
    IndexSet                owned_rows;
    types::global_dof_index first = 0, column_first = 0, column_end = 0;
    bool                    square = false;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    /// Whether some rank has ghost columns (then every product imports).
    bool                      import = false;
    std::vector<std::size_t>  row_start{0};
    std::vector<unsigned int> column;
    std::vector<Number>       value;
    /// With borrow(): the values of the first local row, in the borrowed
    /// matrix (value is then empty).
    const Number *borrowed = nullptr;
    /// The values: value's, or the borrowed matrix's.
    const Number *
    values() const
    {
      return borrowed != nullptr ? borrowed : value.data();
    }
    /// The import buffer, over the column partitioner.
    mutable VectorType ghosted;
    /// The row ranges' buffers of Tvmult() (transposed_vmult_add()).
    mutable std::vector<Number> transposed_scratch;
  };

  template <typename Number>
  template <typename Row>
  void
  DistributedRows<Number>::fill(const IndexSet &rows,
                                const IndexSet &owned_columns,
                                const Row      &row,
                                const MPI_Comm  comm)
  {
    const unsigned int            n = rows.n_elements();
    const types::global_dof_index row_first =
      n > 0 ? rows.nth_index_in_set(0) : 0;
    const types::global_dof_index col_first =
      owned_columns.n_elements() > 0 ? owned_columns.nth_index_in_set(0) : 0;
    const types::global_dof_index col_end =
      col_first + owned_columns.n_elements();
    // First pass: each row's length and whether it holds its diagonal;
    // the ghost columns.
    std::vector<unsigned int>            length(n);
    std::vector<unsigned char>           has_diagonal(n, 0);
    std::vector<types::global_dof_index> ghosts;
    std::mutex                           ghosts_mutex;
    on_row_ranges(n, 4, [&](const unsigned int begin, const unsigned int end) {
      std::vector<types::global_dof_index> mine;
      for (unsigned int k = begin; k < end; ++k)
        row(k, [&](const types::global_dof_index g, const double) {
          ++length[k];
          if (g == row_first + k)
            has_diagonal[k] = 1;
          if (g < col_first || g >= col_end)
            mine.push_back(g);
        });
      std::sort(mine.begin(), mine.end());
      mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
      std::lock_guard<std::mutex> lock(ghosts_mutex);
      ghosts.insert(ghosts.end(), mine.begin(), mine.end());
    });
    std::sort(ghosts.begin(), ghosts.end());
    ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
    setup_columns(rows, owned_columns, ghosts, comm);

    row_start.assign(n + 1, 0);
    for (unsigned int k = 0; k < n; ++k)
      row_start[k + 1] =
        row_start[k] + length[k] + (square && !has_diagonal[k] ? 1 : 0);
    std::vector<unsigned int>().swap(length);
    column.resize(row_start[n]);
    borrowed = nullptr;
    value.assign(row_start[n], Number());
    on_row_ranges(n, 4, [&](const unsigned int begin, const unsigned int end) {
      for (unsigned int k = begin; k < end; ++k)
        {
          std::size_t to = row_start[k];
          if (square)
            column[to++] = k; // the diagonal first
          row(k, [&](const types::global_dof_index g, const double v) {
            if (square && g == first + k)
              value[row_start[k]] = v;
            else
              {
                column[to] = local_column(g);
                value[to]  = v;
                ++to;
              }
          });
        }
    });
  }



  /**
   * The contiguous range of @p n_local indices this rank owns when the
   * ranks of @p comm own consecutive ranges in their order: an IndexSet
   * of the whole space's size. Collective.
   */
  IndexSet
  contiguous_range(const unsigned int n_local, const MPI_Comm comm);
} // namespace Fidus

#endif
