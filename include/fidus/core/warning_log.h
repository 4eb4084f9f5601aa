#ifndef fidus_core_warning_log_h
#define fidus_core_warning_log_h

#include <map>
#include <ostream>
#include <string>

namespace Fidus
{
  /**
   * Warnings of a run, grouped by kind ("Uzawa", "contact", ...).
   *
   * A long run in which every step has the same trouble (for example a
   * dense suspension whose Uzawa loop stops at its cap in every step) would
   * otherwise bury the screen under identical lines. The first
   * @p max_repeats warnings of each kind are written in full, each with its
   * step and time; later ones are counted, and summary() writes one line per
   * kind with the count and the worst value. Nothing is silent: the last
   * full line says that further ones are only counted, and the per-step
   * values are in statistics.csv.
   *
   * Only the writing rank (rank 0) prints; every rank counts, so that a
   * RunSummary is the same on all ranks.
   */
  class WarningLog
  {
  public:
    /// Write to @p out when @p writer is true; @p max_repeats full lines
    /// per kind.
    WarningLog(std::ostream &out, bool writer, unsigned int max_repeats = 10);

    /**
     * Record one warning of @p kind. @p message is the full text (without
     * the "fidus: warning: " prefix); @p value is the quantity that
     * summary() reports the largest of (a residual, a constraint violation),
     * at @p step.
     */
    void
    warn(const std::string &kind,
         const std::string &message,
         unsigned int       step,
         double             value);

    /// How many warnings of @p kind were recorded.
    unsigned int
    count(const std::string &kind) const;

    /// One line per kind that went past max_repeats: count, largest value
    /// and its step. Nothing when every warning was written in full.
    void
    summary() const;

    /// Per kind: how many, the largest value and the step it occurred at.
    struct Tally
    {
      unsigned int count      = 0;
      double       worst      = 0.;
      unsigned int worst_step = 0;
    };

    /// The counters by kind (a checkpoint saves them).
    const std::map<std::string, Tally> &
    get_tallies() const
    {
      return tallies;
    }

    /// Continue counting from @p saved (a resumed run).
    void
    restore(const std::map<std::string, Tally> &saved)
    {
      tallies = saved;
    }

  private:
    std::ostream                &out;
    const bool                   writer;
    const unsigned int           max_repeats;
    std::map<std::string, Tally> tallies;
  };
} // namespace Fidus

#endif
