#ifndef fidus_fluid_cut_element_transposed_vmult_h
#define fidus_fluid_cut_element_transposed_vmult_h

#include <algorithm>
#include <deal.II/base/parallel.h>
#include <deal.II/base/thread_management.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * y += A^T x for a matrix of @p n_rows rows read row by row, @p row(k, f)
   * calling f(column, value) on the entries of row k, its columns below
   * @p n_columns.
   *
   * A transposed product scatters each row into its columns, so rows on
   * different threads write the same entries. Large matrices are therefore
   * cut into a fixed number of row ranges (by the number of rows, not of
   * threads), each scattered into a buffer of its own (@p scratch, kept by
   * the caller between calls), and the buffers summed in the ranges' order:
   * the sums are then the same on any number of threads. The cut element's
   * solver reads B as B^T's transpose this way, and the multigrid's
   * restrictions are P^T products.
   */
  template <typename Number, typename Row>
  void
  transposed_vmult_add(const unsigned int   n_rows,
                       const unsigned int   n_columns,
                       const Row           &row,
                       const Number        *x,
                       Number              *y,
                       std::vector<Number> &scratch)
  {
    // Below this many rows per range the buffers cost more than they save.
    constexpr unsigned int rows_per_range = 16384, max_ranges = 8;
    const unsigned int     n_ranges =
      std::max(1u, std::min(max_ranges, n_rows / rows_per_range));
    if (n_ranges == 1)
      {
        for (unsigned int k = 0; k < n_rows; ++k)
          row(k, [&, xk = x[k]](const unsigned int j, const Number v) {
            y[j] += v * xk;
          });
        return;
      }
    scratch.resize(std::size_t(n_ranges) * n_columns);
    Threads::TaskGroup<void> tasks;
    for (unsigned int r = 0; r < n_ranges; ++r)
      tasks += Threads::new_task([&, r]() {
        Number *buffer = scratch.data() + std::size_t(r) * n_columns;
        std::fill(buffer, buffer + n_columns, Number());
        const unsigned int first = std::size_t(n_rows) * r / n_ranges,
                           last  = std::size_t(n_rows) * (r + 1) / n_ranges;
        for (unsigned int k = first; k < last; ++k)
          row(k, [&, xk = x[k]](const unsigned int j, const Number v) {
            buffer[j] += v * xk;
          });
      });
    tasks.join_all();
    parallel::apply_to_subranges(
      0u,
      n_columns,
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int r = 0; r < n_ranges; ++r)
          {
            const Number *buffer = scratch.data() + std::size_t(r) * n_columns;
            for (unsigned int j = begin; j < end; ++j)
              y[j] += buffer[j];
          }
      },
      4096);
  }
} // namespace Fidus

#endif
