#ifndef fidus_tests_fidus_test_h
#define fidus_tests_fidus_test_h

// Small helpers for fidus tests: each check prints one stable line that says
// OK or FAILED, so that the .output comparison fails when a check fails, and
// the program's exit status is non-zero too.

#include <algorithm>
#include <cmath>
#include <deal.II/base/mpi.h>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace FidusTest
{
  inline int &
  failures()
  {
    static int n = 0;
    return n;
  }

  inline bool
  root()
  {
    return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  }

  /// Send the program's warnings (std::cerr) to warnings.txt in the test's
  /// folder: they carry solver residuals whose last digits vary between
  /// machines, so they must not be part of the compared output. Tests that
  /// care about a warning check the counters of RunSummary instead.
  inline void
  redirect_warnings()
  {
    static std::ofstream file("warnings.txt");
    std::cerr.rdbuf(file.rdbuf());
  }

  /// Check lo <= value <= hi. Stdout (compared with the .output file) gets
  /// only the verdict; the value itself, not stable to the last digit across
  /// machines, goes to the file measured_values.txt in the test's folder.
  inline void
  check_range(const std::string &what,
              const double       value,
              const double       lo,
              const double       hi)
  {
    const bool ok = value >= lo && value <= hi && std::isfinite(value);
    if (!ok)
      ++failures();
    if (root())
      {
        std::cout << what << " in [" << lo << ", " << hi
                  << "]: " << (ok ? "OK" : "FAILED") << std::endl;
        std::ofstream log("measured_values.txt", std::ios::app);
        log << what << " = " << std::setprecision(8) << value << std::endl;
      }
  }

  /// Print a value rounded to @p digits significant digits (for outputs
  /// that are meant to be compared, e.g. 1 and 2 MPI ranks).
  inline void
  print_value(const std::string &what, const double value, const int digits)
  {
    if (root())
      std::cout << what << " = " << std::setprecision(digits) << value
                << std::endl;
  }

  /// The values of the column @p name of the CSV file @p path (a header
  /// line, then rows), one per row.
  inline std::vector<double>
  csv_column(const std::string &path, const std::string &name)
  {
    std::ifstream            in(path);
    std::string              line, item;
    std::vector<std::string> header;
    std::getline(in, line);
    std::stringstream h(line);
    while (std::getline(h, item, ','))
      header.push_back(item);
    const auto k =
      std::find(header.begin(), header.end(), name) - header.begin();
    std::vector<double> values;
    while (std::getline(in, line))
      {
        std::stringstream s(line);
        for (long c = 0; std::getline(s, item, ','); ++c)
          if (c == k)
            values.push_back(std::stod(item));
      }
    return values;
  }

  inline int
  exit_code()
  {
    return failures() == 0 ? 0 : 1;
  }
} // namespace FidusTest

#endif
