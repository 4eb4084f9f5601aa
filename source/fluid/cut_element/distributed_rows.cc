#include <algorithm>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <deal.II/base/parallel.h>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <fidus/fluid/cut_element/transposed_vmult.h>
#include <map>
#include <mutex>
#include <stdexcept>
#include <type_traits>

namespace Fidus
{
  IndexSet
  contiguous_range(const unsigned int n_local, const MPI_Comm comm)
  {
    const std::vector<unsigned int> sizes =
      Utilities::MPI::all_gather(comm, n_local);
    const unsigned int      rank  = Utilities::MPI::this_mpi_process(comm);
    types::global_dof_index first = 0, total = 0;
    for (unsigned int r = 0; r < sizes.size(); ++r)
      {
        if (r == rank)
          first = total;
        total += sizes[r];
      }
    IndexSet range(total);
    range.add_range(first, first + n_local);
    return range;
  }



  template <typename Number>
  void
  DistributedRows<Number>::setup_columns(
    const IndexSet                             &rows,
    const IndexSet                             &owned_columns,
    const std::vector<types::global_dof_index> &ghosts,
    const MPI_Comm                              comm)
  {
    if (!rows.is_contiguous() || !owned_columns.is_contiguous())
      throw std::invalid_argument(
        "DistributedRows: the owned rows and columns must be contiguous "
        "ranges");
    communicator = comm;
    owned_rows   = rows;
    first        = rows.n_elements() > 0 ? rows.nth_index_in_set(0) : 0;
    column_first =
      owned_columns.n_elements() > 0 ? owned_columns.nth_index_in_set(0) : 0;
    column_end = column_first + owned_columns.n_elements();
    square     = rows.size() == owned_columns.size() &&
             Utilities::MPI::min(rows == owned_columns ? 1u : 0u, comm) == 1;
    IndexSet ghost_set(owned_columns.size());
    ghost_set.add_indices(ghosts.begin(), ghosts.end());
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(owned_columns,
                                                                ghost_set,
                                                                comm);
    import      = Utilities::MPI::max(ghosts.empty() ? 0u : 1u, comm) == 1;
    if (import)
      ghosted.reinit(partitioner);
    else
      ghosted.reinit(0);
  }



  template <typename Number>
  void
  DistributedRows<Number>::reinit(
    const IndexSet                             &rows,
    const IndexSet                             &owned_columns,
    const std::vector<std::size_t>             &start,
    const std::vector<types::global_dof_index> &columns,
    const std::vector<double>                  &values,
    const MPI_Comm                              comm)
  {
    if (start.size() != rows.n_elements() + 1 ||
        columns.size() != values.size() || start.back() != columns.size())
      throw std::invalid_argument(
        "DistributedRows::reinit: the rows' arrays do not match the owned "
        "rows");
    fill(
      rows,
      owned_columns,
      [&](const unsigned int k, const auto &f) {
        for (std::size_t e = start[k]; e < start[k + 1]; ++e)
          f(columns[e], values[e]);
      },
      comm);
  }



  template <typename Number>
  template <typename OtherNumber>
  void
  DistributedRows<Number>::copy_from(const DistributedRows<OtherNumber> &other)
  {
    communicator = other.communicator;
    owned_rows   = other.owned_rows;
    first        = other.first;
    column_first = other.column_first;
    column_end   = other.column_end;
    square       = other.square;
    partitioner  = other.partitioner;
    import       = other.import;
    row_start    = other.row_start;
    column       = other.column;
    value.assign(other.values(), other.values() + other.row_start.back());
    borrowed = nullptr;
    if (import)
      ghosted.reinit(partitioner);
    else
      ghosted.reinit(0);
  }



  template <typename Number>
  const Number *
  DistributedRows<Number>::imported(const VectorType &src) const
  {
    if (!import)
      return src.begin();
    std::copy(src.begin(), src.end(), ghosted.begin());
    ghosted.update_ghost_values();
    return ghosted.begin();
  }



  template <typename Number>
  void
  DistributedRows<Number>::vmult(VectorType &dst, const VectorType &src) const
  {
    multiply(dst, src, false);
  }



  template <typename Number>
  void
  DistributedRows<Number>::vmult_add(VectorType       &dst,
                                     const VectorType &src) const
  {
    multiply(dst, src, true);
  }



  template <typename Number>
  void
  DistributedRows<Number>::multiply(VectorType       &dst,
                                    const VectorType &src,
                                    const bool        add) const
  {
    // Row ranges on the threads as deal.II's SparseMatrix::vmult splits
    // them (its grain size), each row summed by one thread in storage
    // order.
    const Number *x = imported(src);
    Number       *y = dst.begin();
    parallel::apply_to_subranges(
      0u,
      local_rows(),
      [&](const unsigned int begin, const unsigned int end) {
        const Number       *v = values() + row_start[begin];
        const unsigned int *c = column.data() + row_start[begin];
        for (unsigned int k = begin; k < end; ++k)
          {
            Number              sum     = add ? y[k] : Number();
            const Number *const row_end = values() + row_start[k + 1];
            while (v != row_end)
              sum += *v++ * x[*c++];
            y[k] = sum;
          }
      },
      internal::SparseMatrixImplementation::minimum_parallel_grain_size);
  }



  template <typename Number>
  void
  DistributedRows<Number>::Tvmult(VectorType &dst, const VectorType &src) const
  {
    dst = Number();
    Tvmult_add(dst, src);
  }



  template <typename Number>
  void
  DistributedRows<Number>::Tvmult_add(VectorType       &dst,
                                      const VectorType &src) const
  {
    // Each row scatters into its columns (on the threads, the same sums
    // on any number of them): the ghost columns' sums go to their owners,
    // which add them to their own.
    Number *y = import ? ghosted.begin() : dst.begin();
    if (import)
      ghosted = Number();
    const Number *v = values();
    transposed_vmult_add(
      local_rows(),
      partitioner->locally_owned_size() + partitioner->n_ghost_indices(),
      [&](const unsigned int k, const auto &f) {
        for (std::size_t e = row_start[k]; e < row_start[k + 1]; ++e)
          f(column[e], v[e]);
      },
      src.begin(),
      y,
      transposed_scratch);
    if (!import)
      return;
    ghosted.compress(VectorOperation::add);
    Number *z = dst.begin();
    for (unsigned int j = 0; j < partitioner->locally_owned_size(); ++j)
      z[j] += y[j];
  }



  template <typename Number>
  std::size_t
  DistributedRows<Number>::memory_consumption() const
  {
    return row_start.capacity() * sizeof(std::size_t) +
           column.capacity() * sizeof(unsigned int) +
           value.capacity() * sizeof(Number) + ghosted.memory_consumption();
  }



  template <typename Number>
  void
  DistributedRows<Number>::for_rows_of_others(
    const std::vector<types::global_dof_index> &rows,
    const std::function<void(types::global_dof_index,
                             const types::global_dof_index *,
                             const double *,
                             std::size_t)>     &f,
    const std::function<bool(types::global_dof_index, types::global_dof_index)>
      &keep) const
  {
    using Index = types::global_dof_index;
    // Each rank's rows end where the next one's begin, in the ranks' order.
    const std::vector<unsigned int> sizes =
      Utilities::MPI::all_gather(communicator, local_rows());
    std::vector<Index> ends(sizes.size());
    Index              total = 0;
    for (unsigned int r = 0; r < sizes.size(); ++r)
      ends[r] = total += sizes[r];
    std::map<unsigned int, std::vector<Index>> requests;
    for (const Index g : rows)
      requests[std::upper_bound(ends.begin(), ends.end(), g) - ends.begin()]
        .push_back(g);
    // Each reply: per row its index, its length and its global columns
    // (first), and its values (second).
    using Packed = std::pair<std::vector<Index>, std::vector<double>>;
    std::map<unsigned int, Packed> replies;
    for (const auto &request :
         Utilities::MPI::some_to_some(communicator, requests))
      {
        Packed &packed = replies[request.first];
        for (const Index g : request.second)
          {
            const unsigned int k = g - first;
            packed.first.push_back(g);
            const std::size_t length_at = packed.first.size();
            packed.first.push_back(0);
            for_row(k, [&](const unsigned int j, const Number v) {
              const Index column = partitioner->local_to_global(j);
              if (keep && !keep(g, column))
                return;
              packed.first.push_back(column);
              packed.second.push_back(v);
              ++packed.first[length_at];
            });
          }
      }
    for (const auto &answer :
         Utilities::MPI::some_to_some(communicator, replies))
      {
        const Packed &packed = answer.second;
        std::size_t   at = 0, value_at = 0;
        while (at < packed.first.size())
          {
            const std::size_t n = packed.first[at + 1];
            f(packed.first[at],
              packed.first.data() + at + 2,
              packed.second.data() + value_at,
              n);
            at += 2 + n;
            value_at += n;
          }
      }
  }



  template <typename Number>
  void
  DistributedRows<Number>::borrow(const IndexSet             &rows,
                                  const SparseMatrix<double> &matrix,
                                  const MPI_Comm              comm)
  {
    if constexpr (!std::is_same_v<Number, double>)
      {
        AssertThrow(false, ExcNotImplemented());
      }
    else
      {
        using Index                    = types::global_dof_index;
        const unsigned int     n       = rows.n_elements();
        const Index            zero    = n > 0 ? rows.nth_index_in_set(0) : 0;
        const SparsityPattern &pattern = matrix.get_sparsity_pattern();
        // The ghost columns, on the threads.
        std::vector<Index> ghosts;
        std::mutex         ghosts_mutex;
        on_row_ranges(n,
                      4,
                      [&](const unsigned int begin, const unsigned int end) {
                        std::vector<Index> mine;
                        for (unsigned int k = begin; k < end; ++k)
                          for (auto it = pattern.begin(zero + k);
                               it != pattern.end(zero + k);
                               ++it)
                            if (it->column() < zero || it->column() >= zero + n)
                              mine.push_back(it->column());
                        std::sort(mine.begin(), mine.end());
                        mine.erase(std::unique(mine.begin(), mine.end()),
                                   mine.end());
                        std::lock_guard<std::mutex> lock(ghosts_mutex);
                        ghosts.insert(ghosts.end(), mine.begin(), mine.end());
                      });
        std::sort(ghosts.begin(), ghosts.end());
        ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
        setup_columns(rows, rows, ghosts, comm);
        // The rows lie one after the other in the matrix's values, each
        // with its diagonal first (a square SparsityPattern's), as this
        // class keeps a square matrix's.
        row_start.assign(n + 1, 0);
        for (unsigned int k = 0; k < n; ++k)
          row_start[k + 1] = row_start[k] + pattern.row_length(zero + k);
        column.resize(row_start[n]);
        on_row_ranges(n,
                      4,
                      [&](const unsigned int begin, const unsigned int end) {
                        for (unsigned int k = begin; k < end; ++k)
                          {
                            std::size_t e = row_start[k];
                            for (auto it = pattern.begin(zero + k);
                                 it != pattern.end(zero + k);
                                 ++it)
                              column[e++] = local_column(it->column());
                          }
                      });
        std::vector<Number>().swap(value);
        borrowed =
          n > 0 ?
            &const_cast<SparseMatrix<double> &>(matrix).diag_element(zero) :
            nullptr;
      }
  }



  template class DistributedRows<double>;
  template class DistributedRows<float>;
  template void
  DistributedRows<float>::copy_from(const DistributedRows<double> &);
  template void
  DistributedRows<double>::copy_from(const DistributedRows<double> &);
} // namespace Fidus
