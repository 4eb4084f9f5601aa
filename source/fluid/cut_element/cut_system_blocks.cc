#include <deal.II/base/exceptions.h>
#include <fidus/fluid/cut_element/cut_system_blocks.h>

namespace Fidus
{
  void
  CutSystemBlocks::reinit(const SparsityPattern            &system,
                          const std::vector<unsigned char> &kind)
  {
    reinit(system, kind, 0, static_cast<unsigned int>(-1));
  }



  void
  CutSystemBlocks::reinit(const SparsityPattern            &system,
                          const std::vector<unsigned char> &kind,
                          const unsigned int                k_first,
                          const unsigned int                k_end)
  {
    this->k_first        = k_first;
    this->k_end          = k_end;
    const unsigned int n = kind.size();
    AssertDimension(system.n_rows(), n);
    this->kind = kind;
    local.assign(n, 0);
    std::vector<unsigned int> rigid;
    k_rows.clear();
    p_rows.clear();
    for (unsigned int i = 0; i < n; ++i)
      {
        auto &list = kind[i] == 0 ? k_rows : kind[i] == 1 ? p_rows : rigid;
        local[i]   = list.size();
        list.push_back(i);
      }
    AssertThrow(rigid.empty() || k_rows.empty() ||
                  rigid.front() > k_rows.back(),
                ExcMessage("The cut element's blocks need the rigid unknowns "
                           "numbered after the fluid's."));
    // K's rows: the velocities, then the rigid unknowns.
    for (const unsigned int i : rigid)
      {
        local[i] = k_rows.size();
        k_rows.push_back(i);
      }

    // Each block's pattern from the system's rows: a column of K's kinds
    // in a row of K goes to K, a pressure column to B^T or P; a pressure
    // row's columns of K's kinds (B) are not kept. The system's rows hold
    // their diagonal first, then ascending columns, and the maps keep the
    // order, so each block's row comes out in order: one pass counts, one
    // writes, nothing is sorted.
    // A velocity row of K this rank does not hold keeps its diagonal
    // alone in K (a square pattern's), and nothing in B^T.
    const auto k_held = [&](const unsigned int i) {
      return kind[i] != 0 || (local[i] >= k_first && local[i] < k_end);
    };
    std::vector<unsigned int> k_lengths(n), p_lengths(n);
    on_row_ranges(n, 4, [&](const unsigned int first, const unsigned int last) {
      for (unsigned int i = first; i < last; ++i)
        for (auto it = system.begin(i), end = system.end(i); it != end; ++it)
          ++(kind[it->column()] == 1 ? p_lengths : k_lengths)[i];
    });
    const auto block_pattern = [&](RowPattern                      &pattern,
                                   const std::vector<unsigned int> &rows,
                                   const unsigned int               n_columns,
                                   const bool pressure_columns) {
      const bool                square = rows.size() == n_columns;
      const bool                on_k   = square && !pressure_columns;
      std::vector<unsigned int> lengths(rows.size());
      for (unsigned int r = 0; r < rows.size(); ++r)
        lengths[r] = !k_held(rows[r]) ?
                       (on_k ? 1 : 0) :
                       (pressure_columns ? p_lengths : k_lengths)[rows[r]];
      pattern.fill_ordered(rows.size(),
                           n_columns,
                           lengths,
                           [&](const unsigned int r, unsigned int *columns) {
                             if (!k_held(rows[r]))
                               return;
                             for (auto it  = system.begin(rows[r]),
                                       end = system.end(rows[r]);
                                  it != end;
                                  ++it)
                               {
                                 const unsigned int j = it->column();
                                 // A square block's diagonal is the system's
                                 // (first in both).
                                 if ((kind[j] == 1) == pressure_columns &&
                                     !(square && j == rows[r]))
                                   *columns++ = local[j];
                               }
                           });
    };
    block_pattern(k_pattern, k_rows, k_rows.size(), false);
    block_pattern(bt_pattern, k_rows, p_rows.size(), true);
    block_pattern(p_pattern, p_rows, p_rows.size(), true);
    k.reinit(k_pattern);
    bt.reinit(bt_pattern);
    p.reinit(p_pattern);
  }



  void
  CutSystemBlocks::add(const size_type  row,
                       const size_type  n_columns,
                       const size_type *columns,
                       const double    *values,
                       const bool       elide_zero_values,
                       const bool       col_indices_are_sorted)
  {
    add_part(row,
             n_columns,
             columns,
             values,
             elide_zero_values,
             col_indices_are_sorted,
             true);
  }



  void
  CutSystemBlocks::add_part(const size_type  row,
                            const size_type  n_columns,
                            const size_type *columns,
                            const double    *values,
                            const bool       elide_zero_values,
                            const bool       col_indices_are_sorted,
                            const bool       summed_rows)
  {
    // The velocity rows of K and B^T: where this rank holds them, from
    // every cell that writes them; the rigid rows and P: from the cells
    // whose sum over the ranks is the system. B, a pressure row's columns
    // of K's kinds, is B^T's transpose and not held.
    if (!(kind[row] == 0 ? owns_velocity_row(row) : summed_rows))
      return;
    // Called from several threads at once (on rows no other thread
    // writes): the split row is the caller's thread's own.
    thread_local std::vector<size_type> k_columns, p_columns;
    thread_local std::vector<double>    k_values, p_values;
    k_columns.clear();
    p_columns.clear();
    k_values.clear();
    p_values.clear();
    const bool on_k = kind[row] != 1;
    for (size_type c = 0; c < n_columns; ++c)
      {
        const size_type j = columns[c];
        if (kind[j] == 1)
          {
            p_columns.push_back(local[j]);
            p_values.push_back(values[c]);
          }
        else if (on_k)
          {
            k_columns.push_back(local[j]);
            k_values.push_back(values[c]);
          }
      }
    // The maps keep the order within each kind (see the class's
    // documentation), so sorted columns stay sorted.
    if (!k_columns.empty())
      k.add(local[row],
            k_columns.size(),
            k_columns.data(),
            k_values.data(),
            elide_zero_values,
            col_indices_are_sorted);
    if (!p_columns.empty())
      (on_k ? bt : p)
        .add(local[row],
             p_columns.size(),
             p_columns.data(),
             p_values.data(),
             elide_zero_values,
             col_indices_are_sorted);
  }



  double
  CutSystemBlocks::diag_element(const size_type i) const
  {
    return kind[i] == 1 ? p.diag_element(local[i]) : k.diag_element(local[i]);
  }
} // namespace Fidus
