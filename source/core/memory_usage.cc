#include <fidus/core/memory_usage.h>
#include <fstream>
#ifdef __GLIBC__
#  include <malloc.h>
#endif
#include <iomanip>
#include <sstream>

namespace Fidus
{
  namespace MemoryUsage
  {
    namespace
    {
      /// The value in kB of the line "key: value kB" of @p file, in bytes.
      std::size_t
      read_kilobytes(const char *file, const std::string &key)
      {
        std::ifstream in(file);
        std::string   line;
        while (std::getline(in, line))
          if (line.compare(0, key.size(), key) == 0 &&
              line.size() > key.size() && line[key.size()] == ':')
            {
              std::istringstream value(line.substr(key.size() + 1));
              std::size_t        kilobytes = 0;
              value >> kilobytes;
              return kilobytes * 1024;
            }
        return 0;
      }
    } // namespace



    std::size_t
    current_bytes()
    {
      return read_kilobytes("/proc/self/status", "VmRSS");
    }



    void
    release_free_memory()
    {
#ifdef __GLIBC__
      malloc_trim(0);
#endif
    }



    std::size_t
    peak_bytes()
    {
      return read_kilobytes("/proc/self/status", "VmHWM");
    }



    std::size_t
    available_bytes()
    {
      return read_kilobytes("/proc/meminfo", "MemAvailable");
    }



    std::string
    format(const double bytes)
    {
      const char *units[] = {"B", "KB", "MB", "GB", "TB"};
      double      value   = bytes;
      unsigned    u       = 0;
      while (value >= 1000. && u < 4)
        {
          value /= 1000.;
          ++u;
        }
      std::ostringstream s;
      s << std::setprecision(3) << value << ' ' << units[u];
      return s.str();
    }
  } // namespace MemoryUsage
} // namespace Fidus
