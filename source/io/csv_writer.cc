#include <cmath>
#include <fidus/core/input_error.h>
#include <fidus/io/csv_writer.h>
#include <iomanip>

namespace Fidus
{
  CsvWriter::CsvWriter(const std::string              &filename,
                       const std::vector<std::string> &columns,
                       const bool                      active)
    : n_columns(columns.size())
    , active(active)
  {
    if (!active)
      return;
    out.open(filename);
    if (!out)
      throw RunError("cannot write the file '" + filename + "'");
    for (std::size_t c = 0; c < columns.size(); ++c)
      out << (c ? "," : "") << columns[c];
    out << '\n' << std::setprecision(15);
  }



  void
  CsvWriter::write_row(const std::vector<double> &values)
  {
    if (!active)
      return;
    for (std::size_t c = 0; c < values.size() && c < n_columns; ++c)
      {
        if (c)
          out << ',';
        // Integers (step, id, counts) are written without an exponent.
        if (values[c] == std::round(values[c]) && std::abs(values[c]) < 1e15)
          out << static_cast<long long>(values[c]);
        else
          out << values[c];
      }
    out << '\n';
    out.flush();
  }
} // namespace Fidus
