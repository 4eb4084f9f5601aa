#ifndef fidus_fluid_cut_element_row_ranges_h
#define fidus_fluid_cut_element_row_ranges_h

#include <algorithm>
#include <cstddef>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
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
} // namespace Fidus

#endif
