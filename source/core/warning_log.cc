#include <fidus/core/warning_log.h>

namespace Fidus
{
  WarningLog::WarningLog(std::ostream      &out_,
                         const bool         writer_,
                         const unsigned int max_repeats_)
    : out(out_)
    , writer(writer_)
    , max_repeats(max_repeats_)
  {}



  void
  WarningLog::warn(const std::string &kind,
                   const std::string &message,
                   const unsigned int step,
                   const double       value)
  {
    Tally &t = tallies[kind];
    ++t.count;
    if (t.count == 1 || value > t.worst)
      {
        t.worst      = value;
        t.worst_step = step;
      }
    if (!writer || t.count > max_repeats)
      return;
    out << "fidus: warning: " << message;
    if (t.count == max_repeats)
      out << " [" << max_repeats << " such warnings (" << kind
          << "); further ones are counted and summarised at the end]";
    out << std::endl;
  }



  unsigned int
  WarningLog::count(const std::string &kind) const
  {
    const auto it = tallies.find(kind);
    return it == tallies.end() ? 0 : it->second.count;
  }



  void
  WarningLog::summary() const
  {
    if (!writer)
      return;
    for (const auto &[kind, t] : tallies)
      if (t.count > max_repeats)
        out << "fidus: warning: " << t.count << " warnings (" << kind
            << ") in this run, " << max_repeats
            << " of them written above; the largest value was " << t.worst
            << " at step " << t.worst_step << std::endl;
  }
} // namespace Fidus
