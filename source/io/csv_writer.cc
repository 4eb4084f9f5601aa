#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
    out << header(columns) << '\n' << std::setprecision(15);
  }



  CsvWriter::CsvWriter(const std::string              &filename,
                       const std::vector<std::string> &columns,
                       const bool                      active,
                       const unsigned int              last_step)
    : n_columns(columns.size())
    , active(active)
  {
    if (!active)
      return;
    std::ifstream in(filename);
    std::string   line;
    if (!in || !std::getline(in, line) || line != header(columns))
      throw RunError("cannot continue '" + filename +
                     "': it is missing or its header is not '" +
                     header(columns) + "'");
    const std::string kept_name = filename + ".resume";
    {
      std::ofstream kept(kept_name);
      kept << line << '\n';
      // Keep a row only if it is whole (as many fields as the header) and
      // its step parses and is not beyond the checkpoint: a run killed in
      // the middle of a row leaves a partial last line, which is dropped.
      while (std::getline(in, line))
        {
          if (static_cast<std::size_t>(
                std::count(line.begin(), line.end(), ',')) +
                1 !=
              n_columns)
            continue;
          const std::string step_text = line.substr(0, line.find(','));
          char             *end       = nullptr;
          const long long   step = std::strtoll(step_text.c_str(), &end, 10);
          if (step_text.empty() || *end != '\0' || step < 0)
            continue;
          if (step <= static_cast<long long>(last_step))
            kept << line << '\n';
        }
      if (!kept)
        throw RunError("cannot write the file '" + kept_name + "'");
    }
    in.close();
    if (std::rename(kept_name.c_str(), filename.c_str()) != 0)
      throw RunError("cannot rename '" + kept_name + "' to '" + filename + "'");
    out.open(filename, std::ios::app);
    if (!out)
      throw RunError("cannot write the file '" + filename + "'");
    out << std::setprecision(15);
  }



  std::string
  CsvWriter::header(const std::vector<std::string> &columns)
  {
    std::string h;
    for (std::size_t c = 0; c < columns.size(); ++c)
      h += (c ? "," : "") + columns[c];
    return h;
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
