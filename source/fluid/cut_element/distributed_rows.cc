#include <algorithm>
#include <fidus/fluid/cut_element/distributed_rows.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <stdexcept>

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
  DistributedRows<Number>::reinit(
    const IndexSet                             &rows,
    const IndexSet                             &owned_columns,
    const std::vector<std::size_t>             &start,
    const std::vector<types::global_dof_index> &columns,
    const std::vector<double>                  &values,
    const MPI_Comm                              comm)
  {
    if (!rows.is_contiguous() || !owned_columns.is_contiguous() ||
        start.size() != rows.n_elements() + 1 ||
        columns.size() != values.size() || start.back() != columns.size())
      throw std::invalid_argument(
        "DistributedRows::reinit: the owned rows and columns must be "
        "contiguous ranges and the rows' arrays match them");
    communicator = comm;
    owned_rows   = rows;
    first        = rows.n_elements() > 0 ? rows.nth_index_in_set(0) : 0;
    square       = rows.size() == owned_columns.size() &&
             Utilities::MPI::min(rows == owned_columns ? 1u : 0u, comm) == 1;

    std::vector<types::global_dof_index> ghosts;
    for (const auto c : columns)
      if (!owned_columns.is_element(c))
        ghosts.push_back(c);
    std::sort(ghosts.begin(), ghosts.end());
    ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
    IndexSet ghost_set(owned_columns.size());
    ghost_set.add_indices(ghosts.begin(), ghosts.end());
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(owned_columns,
                                                                ghost_set,
                                                                comm);
    import      = Utilities::MPI::max(ghosts.empty() ? 0u : 1u, comm) == 1;

    const unsigned int n = rows.n_elements();
    row_start.assign(n + 1, 0);
    for (unsigned int k = 0; k < n; ++k)
      {
        bool diagonal = false;
        if (square)
          for (std::size_t e = start[k]; e < start[k + 1]; ++e)
            diagonal = diagonal || columns[e] == first + k;
        row_start[k + 1] =
          row_start[k] + start[k + 1] - start[k] + (square && !diagonal);
      }
    column.resize(row_start[n]);
    value.assign(row_start[n], Number());
    on_row_ranges(n, 4, [&](const unsigned int begin, const unsigned int end) {
      for (unsigned int k = begin; k < end; ++k)
        {
          std::size_t to = row_start[k];
          if (square)
            column[to++] = k; // the diagonal first; its value below
          for (std::size_t e = start[k]; e < start[k + 1]; ++e)
            if (square && columns[e] == first + k)
              value[row_start[k]] = values[e];
            else
              {
                column[to] = partitioner->global_to_local(columns[e]);
                value[to]  = values[e];
                ++to;
              }
        }
    });
    if (import)
      ghosted.reinit(partitioner);
    else
      ghosted.reinit(0);
  }



  template <typename Number>
  template <typename OtherNumber>
  void
  DistributedRows<Number>::copy_from(const DistributedRows<OtherNumber> &other)
  {
    communicator = other.communicator;
    owned_rows   = other.owned_rows;
    first        = other.first;
    square       = other.square;
    partitioner  = other.partitioner;
    import       = other.import;
    row_start    = other.row_start;
    column       = other.column;
    value.assign(other.value.begin(), other.value.end());
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
    dst = Number();
    vmult_add(dst, src);
  }



  template <typename Number>
  void
  DistributedRows<Number>::vmult_add(VectorType       &dst,
                                     const VectorType &src) const
  {
    const Number *x = imported(src);
    Number       *y = dst.begin();
    on_row_ranges(local_rows(),
                  4,
                  [&](const unsigned int begin, const unsigned int end) {
                    for (unsigned int k = begin; k < end; ++k)
                      {
                        Number sum = 0;
                        for (std::size_t e = row_start[k]; e < row_start[k + 1];
                             ++e)
                          sum += value[e] * x[column[e]];
                        y[k] += sum;
                      }
                  });
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
    // Each row scatters into its columns: the ghost columns' sums go to
    // their owners, which add them to their own.
    Number *y = import ? ghosted.begin() : dst.begin();
    if (import)
      ghosted = Number();
    const Number *x = src.begin();
    for (unsigned int k = 0; k < local_rows(); ++k)
      for (std::size_t e = row_start[k]; e < row_start[k + 1]; ++e)
        y[column[e]] += value[e] * x[k];
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



  template class DistributedRows<double>;
  template class DistributedRows<float>;
  template void
  DistributedRows<float>::copy_from(const DistributedRows<double> &);
  template void
  DistributedRows<double>::copy_from(const DistributedRows<double> &);
} // namespace Fidus
