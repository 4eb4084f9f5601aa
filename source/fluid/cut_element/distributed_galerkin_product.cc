#include <algorithm>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <deal.II/base/mpi.templates.h>
#include <fidus/fluid/cut_element/component_coupling.h>
#include <fidus/fluid/cut_element/distributed_galerkin_product.h>
#include <fidus/fluid/cut_element/sparse_matrix_rows.h>
#include <fidus/fluid/cut_element/sparse_rows.h>
#include <map>
#include <stdexcept>
#include <utility>

namespace Fidus
{
  namespace
  {
    using Index = types::global_dof_index;

    /**
     * Rows sent to another rank: for each row its global index, its
     * number of entries and their global columns (in #first), and the
     * entries' values (in #second).
     */
    using PackedRows = std::pair<std::vector<Index>, std::vector<double>>;

    void
    pack_row(PackedRows       &packed,
             const Index       row,
             const Index      *columns,
             const double     *values,
             const std::size_t n)
    {
      packed.first.push_back(row);
      packed.first.push_back(n);
      packed.first.insert(packed.first.end(), columns, columns + n);
      packed.second.insert(packed.second.end(), values, values + n);
    }

    /// f(row, columns, values, n) for each row of @p packed.
    template <typename F>
    void
    for_packed_row(const PackedRows &packed, const F &f)
    {
      std::size_t at = 0, value_at = 0;
      while (at < packed.first.size())
        {
          const Index       row = packed.first[at];
          const std::size_t n   = packed.first[at + 1];
          f(row,
            packed.first.data() + at + 2,
            packed.second.data() + value_at,
            n);
          at += 2 + n;
          value_at += n;
        }
    }

    /// The rank owning each index of a space split in contiguous ranges
    /// in the order of the ranks, from every rank's range size.
    class Owners
    {
    public:
      Owners(const IndexSet &owned, const MPI_Comm comm)
      {
        const auto sizes = Utilities::MPI::all_gather(comm,
                                                      static_cast<unsigned int>(
                                                        owned.n_elements()));
        ends.resize(sizes.size());
        Index total = 0;
        for (unsigned int r = 0; r < sizes.size(); ++r)
          ends[r] = total += sizes[r];
      }
      unsigned int
      operator()(const Index i) const
      {
        return std::upper_bound(ends.begin(), ends.end(), i) - ends.begin();
      }

    private:
      std::vector<Index> ends;
    };

    /// The global columns and values of local row @p k of @p m.
    void
    global_row(const DistributedRows<double> &m,
               const unsigned int             k,
               std::vector<Index>            &columns,
               std::vector<double>           &values)
    {
      columns.clear();
      values.clear();
      m.for_row(k, [&](const unsigned int j, const double v) {
        columns.push_back(m.column_partitioner().local_to_global(j));
        values.push_back(v);
      });
    }

    /**
     * P's rows for every column of A (A's local column numbering: A's
     * own rows, which are P's, then its ghost columns, fetched from their
     * owners), with P's columns renumbered compactly: @p coarse lists the
     * coarse global columns they reach, in order.
     */
    template <typename RowsOfA>
    SparseRows
    prolongation_by_column(const RowsOfA                 &a,
                           const DistributedRows<double> &p,
                           std::vector<Index>            &coarse)
    {
      const auto  comm    = a.get_mpi_communicator();
      const auto &columns = a.column_partitioner();
      // Ask each owner for the rows of A's ghost columns (grouped by
      // owner, in ascending order, as the partitioner lists them).
      std::map<unsigned int, std::vector<Index>> requests;
      {
        auto ghost = columns.ghost_indices().begin();
        for (const auto &target : columns.ghost_targets())
          for (unsigned int k = 0; k < target.second; ++k, ++ghost)
            requests[target.first].push_back(*ghost);
      }
      const auto asked = Utilities::MPI::some_to_some(comm, requests);
      std::map<unsigned int, PackedRows> replies;
      std::vector<Index>                 row_columns;
      std::vector<double>                row_values;
      for (const auto &request : asked)
        for (const Index g : request.second)
          {
            global_row(p, g - p.first_row(), row_columns, row_values);
            pack_row(replies[request.first],
                     g,
                     row_columns.data(),
                     row_values.data(),
                     row_columns.size());
          }
      const auto answered = Utilities::MPI::some_to_some(comm, replies);

      // The compact columns: P's own local columns (its owned coarse
      // columns, then its ghost ones), then the columns only the fetched
      // rows reach.
      const auto        &pc  = p.column_partitioner();
      const unsigned int n_p = pc.locally_owned_size() + pc.n_ghost_indices();
      const auto         p_knows = [&pc](const Index g) {
        return pc.in_local_range(g) || pc.is_ghost_entry(g);
      };
      std::vector<Index> extra;
      for (const auto &answer : answered)
        for_packed_row(answer.second,
                       [&](const Index,
                           const Index *cols,
                           const double *,
                           const std::size_t n) {
                         for (std::size_t e = 0; e < n; ++e)
                           if (!p_knows(cols[e]))
                             extra.push_back(cols[e]);
                       });
      std::sort(extra.begin(), extra.end());
      extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
      coarse.resize(n_p + extra.size());
      for (unsigned int j = 0; j < n_p; ++j)
        coarse[j] = pc.local_to_global(j);
      std::copy(extra.begin(), extra.end(), coarse.begin() + n_p);

      // The rows in A's local column numbering: P's own rows as they are,
      // then the fetched ones in the order of A's ghost columns.
      const unsigned int n_own = p.local_rows();
      const unsigned int n_all = n_own + columns.n_ghost_indices();
      SparseRows         out;
      out.n_rows = n_all;
      out.n_cols = coarse.size();
      out.start.assign(n_all + 1, 0);
      for (unsigned int k = 0; k < n_own; ++k)
        out.start[k + 1] = out.start[k] + p.row_length(k);
      std::vector<std::pair<const Index *, const double *>> fetched(n_all -
                                                                    n_own);
      for (const auto &answer : answered)
        for_packed_row(answer.second,
                       [&](const Index       row,
                           const Index      *cols,
                           const double     *vals,
                           const std::size_t n) {
                         const unsigned int k = columns.global_to_local(row);
                         out.start[k + 1]     = n;
                         fetched[k - n_own]   = {cols, vals};
                       });
      for (unsigned int k = n_own; k < n_all; ++k)
        out.start[k + 1] += out.start[k];
      out.column.resize(out.start[n_all]);
      out.value.resize(out.start[n_all]);
      for (unsigned int k = 0; k < n_own; ++k)
        {
          std::size_t to = out.start[k];
          p.for_row(k, [&](const unsigned int j, const double v) {
            out.column[to] = j;
            out.value[to]  = v;
            ++to;
          });
        }
      for (unsigned int k = n_own; k < n_all; ++k)
        for (std::size_t e = 0; e < out.start[k + 1] - out.start[k]; ++e)
          {
            const Index g = fetched[k - n_own].first[e];
            out.column[out.start[k] + e] =
              p_knows(g) ?
                pc.global_to_local(g) :
                n_p + (std::lower_bound(extra.begin(), extra.end(), g) -
                       extra.begin());
            out.value[out.start[k] + e] = fetched[k - n_own].second[e];
          }
      return out;
    }
  } // namespace



  template <typename RowsOfA>
  void
  distributed_galerkin_product(const RowsOfA                    &a,
                               const DistributedRows<double>    &p,
                               const IndexSet                   &coarse_owned,
                               DistributedRows<double>          &c,
                               const std::vector<unsigned char> &component)
  {
    if (!(a.locally_owned_rows() == p.locally_owned_rows()) ||
        !(a.locally_owned_rows() ==
          a.column_partitioner().locally_owned_range()))
      throw std::invalid_argument(
        "distributed_galerkin_product: A must be square, and P split "
        "among the ranks as A");
    const auto         comm = a.get_mpi_communicator();
    const unsigned int n    = a.local_rows();
    std::vector<Index> coarse; // compact coarse column -> global
    const SparseRows   product = [&]() {
      const SparseRows p_rows = prolongation_by_column(a, p, coarse);
      // A P on this rank's rows.
      const auto      &a_columns = a.column_partitioner();
      const SparseRows ap        = multiply(
        n,
        [&](const unsigned int i, const auto &f) {
          const Index gi = a.first_row() + i;
          a.for_row(i, [&](const unsigned int j, const double v) {
            if (component.empty() ||
                couples_within_component(component,
                                         gi,
                                         a_columns.local_to_global(j)))
              f(j, v);
          });
        },
        p_rows);
      // P^T (A P) from this rank's fine rows: its own rows of P, whose
      // transpose has a row per compact coarse column.
      SparseRows own;
      own.n_rows = n;
      own.n_cols = p_rows.n_cols;
      own.start.assign(p_rows.start.begin(), p_rows.start.begin() + n + 1);
      own.column.assign(p_rows.column.begin(),
                        p_rows.column.begin() + own.start[n]);
      own.value.assign(p_rows.value.begin(),
                       p_rows.value.begin() + own.start[n]);
      const SparseRows pt = transpose(own);
      return multiply(
        pt.n_rows,
        [&pt](const unsigned int i, const auto &f) {
          for (std::size_t k = pt.start[i]; k < pt.start[i + 1]; ++k)
            f(pt.column[k], pt.value[k]);
        },
        ap);
    }();

    // Each coarse row to its owner. A row owned here is the product's row
    // as it stands, unless other ranks sent parts of it: those rows are
    // summed here, by column.
    const Owners       owners(coarse_owned, comm);
    const unsigned int me = Utilities::MPI::this_mpi_process(comm);
    const Index        first =
      coarse_owned.n_elements() > 0 ? coarse_owned.nth_index_in_set(0) : 0;
    std::vector<int> product_row(coarse_owned.n_elements(), -1);
    std::map<unsigned int, PackedRows> sends;
    std::vector<Index>                 row_columns;
    for (unsigned int r = 0; r < product.n_rows; ++r)
      {
        const Index g     = coarse[r];
        const auto  begin = product.start[r], end = product.start[r + 1];
        if (begin == end)
          continue;
        const unsigned int owner = owners(g);
        if (owner == me)
          {
            product_row[g - first] = r;
            continue;
          }
        row_columns.clear();
        for (std::size_t e = begin; e < end; ++e)
          row_columns.push_back(coarse[product.column[e]]);
        pack_row(sends[owner],
                 g,
                 row_columns.data(),
                 product.value.data() + begin,
                 end - begin);
      }
    std::map<Index, std::vector<std::pair<Index, double>>> summed;
    for (const auto &received : Utilities::MPI::some_to_some(comm, sends))
      for_packed_row(received.second,
                     [&](const Index       row,
                         const Index      *cols,
                         const double     *vals,
                         const std::size_t n_entries) {
                       auto &entries = summed[row];
                       for (std::size_t e = 0; e < n_entries; ++e)
                         entries.emplace_back(cols[e], vals[e]);
                     });
    for (auto &[row, entries] : summed)
      {
        if (const int r = product_row[row - first]; r >= 0)
          for (std::size_t e = product.start[r]; e < product.start[r + 1]; ++e)
            entries.emplace_back(coarse[product.column[e]], product.value[e]);
        std::sort(entries.begin(), entries.end());
        std::vector<std::pair<Index, double>> merged;
        for (const auto &e : entries)
          if (!merged.empty() && merged.back().first == e.first)
            merged.back().second += e.second;
          else
            merged.push_back(e);
        entries.swap(merged);
      }
    c.fill(
      coarse_owned,
      coarse_owned,
      [&](const unsigned int k, const auto &f) {
        if (const auto s = summed.find(first + k); s != summed.end())
          for (const auto &e : s->second)
            f(e.first, e.second);
        else if (const int r = product_row[k]; r >= 0)
          for (std::size_t e = product.start[r]; e < product.start[r + 1]; ++e)
            f(coarse[product.column[e]], product.value[e]);
      },
      comm);
  }



  template void
  distributed_galerkin_product(const DistributedRows<double> &,
                               const DistributedRows<double> &,
                               const IndexSet &,
                               DistributedRows<double> &,
                               const std::vector<unsigned char> &);
  template void
  distributed_galerkin_product(const SparseMatrixRows &,
                               const DistributedRows<double> &,
                               const IndexSet &,
                               DistributedRows<double> &,
                               const std::vector<unsigned char> &);
} // namespace Fidus
