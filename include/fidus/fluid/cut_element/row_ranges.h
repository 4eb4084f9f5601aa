#ifndef fidus_fluid_cut_element_row_ranges_h
#define fidus_fluid_cut_element_row_ranges_h

#include <algorithm>
#include <cstddef>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * Call @p f(first, last) on consecutive ranges of the rows 0 to
   * @p n_rows, @p ranges_per_thread of them per thread
   * (MultithreadInfo::n_threads()), as tasks, and wait for all. The cut
   * element's set-up fills matrices and patterns row by row this way: each
   * row is computed by one task, the same whatever the number of threads.
   */
  template <typename F>
  void
  on_row_ranges(const unsigned int n_rows,
                const unsigned int ranges_per_thread,
                const F           &f)
  {
    const unsigned int n_ranges =
      std::max(1u,
               std::min(n_rows,
                        ranges_per_thread * MultithreadInfo::n_threads()));
    Threads::TaskGroup<void> tasks;
    for (unsigned int k = 0; k < n_ranges; ++k)
      {
        const unsigned int first = std::size_t(n_rows) * k / n_ranges,
                           last  = std::size_t(n_rows) * (k + 1) / n_ranges;
        tasks += Threads::new_task([&f, first, last]() { f(first, last); });
      }
    tasks.join_all();
  }

  /**
   * Fill @p pattern (@p n_rows x @p n_cols) from compressed rows: row i's
   * columns, in any order, are columns[start[i]] to columns[start[i + 1]]
   * (exclusive). As SparsityPattern::copy_from does, a square pattern also
   * gets every diagonal entry.
   */
  inline void
  pattern_from_rows(SparsityPattern                 &pattern,
                    const unsigned int               n_rows,
                    const unsigned int               n_cols,
                    const std::vector<unsigned int> &columns,
                    const std::vector<std::size_t>  &start)
  {
    struct RowView
    {
      using const_iterator = const unsigned int *;
      const unsigned int *first, *last;
      const_iterator
      begin() const
      {
        return first;
      }
      const_iterator
      end() const
      {
        return last;
      }
    };
    std::vector<RowView> views;
    views.reserve(n_rows);
    for (unsigned int i = 0; i < n_rows; ++i)
      views.push_back(
        {columns.data() + start[i], columns.data() + start[i + 1]});
    pattern.copy_from(n_rows, n_cols, views.begin(), views.end());
  }
} // namespace Fidus

#endif
