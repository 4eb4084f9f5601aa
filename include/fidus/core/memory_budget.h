#ifndef fidus_core_memory_budget_h
#define fidus_core_memory_budget_h

#include <mpi.h>
#include <string>

namespace Fidus
{
  /// How many ranks of @p comm share this rank's machine (its memory and
  /// cores). Collective on @p comm.
  unsigned int
  ranks_on_this_machine(MPI_Comm comm);

  /**
   * How much more memory a rank may allocate, so that a run that would not
   * fit says so instead of being killed by the operating system.
   *
   * With a limit per rank (the entry 'Fluid/Linear solver/Memory per
   * rank'), a rank may grow to that limit. Without one (auto), the ranks of
   * one machine share what the machine still has available (MemAvailable,
   * or what is left under a control group's limit when that is lower, as
   * in a batch job), less a tenth kept for the rest of the time step. Where
   * the operating system reports neither, the budget is unlimited.
   */
  class MemoryBudget
  {
  public:
    /// @p limit_per_rank in bytes, 0 for auto. Collective on @p comm (it
    /// counts the ranks that share each machine).
    MemoryBudget(double limit_per_rank, MPI_Comm comm);

    /// Bytes this rank may still allocate now, >= 0; infinite when
    /// unknown.
    double
    free_bytes() const;

    /// Where the budget comes from, for messages: "the entry ..." or "the
    /// X GB this machine has available, shared by its N ranks".
    std::string
    source() const;

    /**
     * Hand the memory this rank has freed back to the operating system
     * (MemoryUsage::release_free_memory()) only when some rank of @p comm
     * has less than twice @p needed_bytes left. Memory handed back is
     * taken again by the next step page by page, each page cleared by the
     * kernel: in the cut element's dense 3D scene that cost a sixth of a
     * step. Kept, freed memory is reused by this process's own next
     * allocations. Collective on @p comm. (The fictitious domain still
     * hands it back at once: on its 3D scenes, at a few hundred MB per
     * rank, keeping it changed neither the time nor the peak.)
     */
    void
    release_freed_memory_if_short(double needed_bytes, MPI_Comm comm) const;

  private:
    const double       limit_per_rank;
    const unsigned int ranks_on_machine;
  };
} // namespace Fidus

#endif
