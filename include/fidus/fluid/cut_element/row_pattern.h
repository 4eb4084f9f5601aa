#ifndef fidus_fluid_cut_element_row_pattern_h
#define fidus_fluid_cut_element_row_pattern_h

#include <algorithm>
#include <deal.II/lac/sparsity_pattern.h>
#include <fidus/fluid/cut_element/row_ranges.h>
#include <vector>

namespace Fidus
{
  using namespace dealii;

  /**
   * A deal.II SparsityPattern that fills itself row by row on the
   * machine's threads.
   *
   * SparsityPattern::copy_from() is serial: it copies every row into
   * place, then compress() allocates the pattern a second time, sorts each
   * row and copies it again, on one thread. The cut element builds its
   * system's pattern, the blocks its preconditioner copies and the
   * multigrid's Galerkin products that way, and in a dense 3D suspension
   * those copies alone took a seventh of a step (25.9 s of 178 s at
   * 188 million entries). fill() writes the compressed arrays once and
   * directly: each row's columns sorted, the diagonal first in a square
   * pattern (as compress() leaves them), every row on one task. The result
   * is the pattern copy_from() gives for the same rows (test
   * fluid/row_pattern).
   */
  class RowPattern : public SparsityPattern
  {
  public:
    /**
     * Become the compressed @p n_rows × @p n_cols pattern whose row i has
     * the columns that @p columns(i, f) passes to f (each once, in any
     * order); a square pattern also gets every diagonal entry, as
     * copy_from() gives it. @p columns is called twice per row, from the
     * threads (MultithreadInfo::n_threads()).
     */
    template <typename Columns>
    void
    fill(const unsigned int n_rows,
         const unsigned int n_cols,
         const Columns     &columns)
    {
      const bool                square = n_rows == n_cols;
      std::vector<unsigned int> lengths(n_rows);
      on_row_ranges(n_rows,
                    4,
                    [&](const unsigned int first, const unsigned int last) {
                      for (unsigned int i = first; i < last; ++i)
                        {
                          unsigned int length   = 0;
                          bool         diagonal = false;
                          columns(i, [&](const unsigned int j) {
                            ++length;
                            diagonal = diagonal || j == i;
                          });
                          lengths[i] = length + (square && !diagonal ? 1 : 0);
                        }
                    });
      // The arrays at their final sizes (a square pattern's diagonal
      // first in each row).
      SparsityPattern::reinit(n_rows, n_cols, lengths);
      if (n_rows == 0 || n_cols == 0)
        return;
      on_row_ranges(n_rows,
                    4,
                    [&](const unsigned int first, const unsigned int last) {
                      std::vector<unsigned int> row;
                      for (unsigned int i = first; i < last; ++i)
                        {
                          row.clear();
                          columns(i, [&](const unsigned int j) {
                            if (!square || j != i)
                              row.push_back(j);
                          });
                          std::sort(row.begin(), row.end());
                          std::copy(row.begin(),
                                    row.end(),
                                    colnums.get() + rowstart[i] +
                                      (square ? 1 : 0));
                        }
                    });
      compressed = true;
    }

    /**
     * fill() for a caller that already knows each row: row i has
     * @p lengths[i] entries (a square pattern's diagonal counted), and
     * @p write(i, columns), called once per row from the threads, writes
     * its columns in ascending order to columns, without the diagonal of
     * a square pattern (which goes first by itself). Nothing is counted
     * or sorted here: the cut element's solver copies the blocks of its
     * system this way, whose rows come out in order.
     */
    template <typename Write>
    void
    fill_ordered(const unsigned int               n_rows,
                 const unsigned int               n_cols,
                 const std::vector<unsigned int> &lengths,
                 const Write                     &write)
    {
      const bool square = n_rows == n_cols;
      SparsityPattern::reinit(n_rows, n_cols, lengths);
      if (n_rows == 0 || n_cols == 0)
        return;
      on_row_ranges(n_rows,
                    4,
                    [&](const unsigned int first, const unsigned int last) {
                      for (unsigned int i = first; i < last; ++i)
                        write(i,
                              colnums.get() + rowstart[i] + (square ? 1 : 0));
                    });
      compressed = true;
    }

    /**
     * fill() from compressed rows: row i's columns, in any order, are
     * @p columns[@p start[i]] to @p columns[@p start[i + 1]] (exclusive).
     */
    void
    fill_from_rows(const unsigned int               n_rows,
                   const unsigned int               n_cols,
                   const std::vector<unsigned int> &columns,
                   const std::vector<std::size_t>  &start)
    {
      fill(n_rows, n_cols, [&](const unsigned int i, const auto &f) {
        for (std::size_t k = start[i]; k < start[i + 1]; ++k)
          f(columns[k]);
      });
    }
  };
} // namespace Fidus

#endif
