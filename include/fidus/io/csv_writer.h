#ifndef fidus_io_csv_writer_h
#define fidus_io_csv_writer_h

#include <fstream>
#include <string>
#include <vector>

namespace Fidus
{
  /**
   * A CSV file with a header line, written by one MPI rank (the caller
   * decides which: the others pass active = false and write nothing).
   * Numbers are written with 15 significant digits, so that the files can be
   * compared and post-processed without loss (interface.md asks for >= 12).
   * Every row is flushed so that a run that stops keeps all rows so far.
   */
  class CsvWriter
  {
  public:
    /// Create @p filename with the given column names (if @p active).
    CsvWriter(const std::string              &filename,
              const std::vector<std::string> &columns,
              const bool                      active);

    /**
     * Continue @p filename for a run resumed at step @p last_step: the rows
     * whose first column (the step) is above @p last_step are dropped
     * (they are computed again), the file is rewritten under a temporary
     * name and renamed, and new rows are appended. So the file has every
     * step once, whatever step the earlier run had reached. The header must
     * be @p columns.
     */
    CsvWriter(const std::string              &filename,
              const std::vector<std::string> &columns,
              const bool                      active,
              unsigned int                    last_step);

    /// Append one row; the number of values must match the header.
    void
    write_row(const std::vector<double> &values);

  private:
    /// The header line for @p columns.
    static std::string
    header(const std::vector<std::string> &columns);

    std::ofstream out;
    std::size_t   n_columns;
    bool          active;
  };
} // namespace Fidus

#endif
