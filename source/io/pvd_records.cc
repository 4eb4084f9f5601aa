#include <cctype>
#include <cstdlib>
#include <fidus/io/pvd_records.h>
#include <fstream>
#include <sstream>

namespace Fidus
{
  long
  step_of_output_file(const std::string &file)
  {
    const std::size_t slash = file.find_last_of('/');
    const std::string base =
      slash == std::string::npos ? file : file.substr(slash + 1);
    const std::size_t dot = base.find('.');
    const std::string stem =
      dot == std::string::npos ? base : base.substr(0, dot);
    std::size_t end = stem.size();
    while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1])))
      --end;
    std::size_t begin = end;
    while (begin > 0 &&
           std::isdigit(static_cast<unsigned char>(stem[begin - 1])))
      --begin;
    if (begin == end)
      return -1;
    return std::stol(stem.substr(begin, end - begin));
  }



  std::vector<std::pair<double, std::string>>
  read_pvd_records(const std::string &pvd_file, const unsigned int last_step)
  {
    std::vector<std::pair<double, std::string>> records;
    std::ifstream                               in(pvd_file);
    std::string                                 line;
    auto attribute = [](const std::string &l, const std::string &name) {
      const std::string key = name + "=\"";
      const std::size_t b   = l.find(key);
      if (b == std::string::npos)
        return std::string();
      const std::size_t e = l.find('"', b + key.size());
      return l.substr(b + key.size(), e - b - key.size());
    };
    while (std::getline(in, line))
      {
        if (line.find("<DataSet") == std::string::npos)
          continue;
        const std::string time = attribute(line, "timestep");
        const std::string file = attribute(line, "file");
        const long        step = step_of_output_file(file);
        if (time.empty() || file.empty() || step < 0 ||
            step > static_cast<long>(last_step))
          continue;
        // A damaged entry (a run killed while writing the file) is dropped.
        char        *end = nullptr;
        const double t   = std::strtod(time.c_str(), &end);
        if (*end != '\0')
          continue;
        records.emplace_back(t, file);
      }
    return records;
  }
} // namespace Fidus
