#include <cmath>
#include <cstdio>
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
      while (std::getline(in, line))
        {
          const std::size_t comma = line.find(',');
          if (line.empty() || comma == 0)
            continue;
          if (std::stoll(line.substr(0, comma)) <= (long long)last_step)
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
