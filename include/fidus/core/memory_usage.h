#ifndef fidus_core_memory_usage_h
#define fidus_core_memory_usage_h

#include <cstddef>
#include <string>

namespace Fidus
{
  /**
   * The memory of this process and of its machine, as the operating system
   * reports it (Linux: /proc/self/status and /proc/meminfo). Where these are
   * not available every function returns 0, and callers treat 0 as
   * "unknown".
   */
  namespace MemoryUsage
  {
    /// Resident memory of this process now, in bytes (VmRSS).
    std::size_t
    current_bytes();

    /// Largest resident memory of this process so far, in bytes (VmHWM).
    std::size_t
    peak_bytes();

    /// Memory the machine can still give to new allocations without
    /// swapping, in bytes (MemAvailable).
    std::size_t
    available_bytes();

    /// Hand the heap's free pages back to the operating system (glibc:
    /// malloc_trim; elsewhere nothing). Many small blocks freed in the
    /// middle of the heap (a set-up's scratch) otherwise stay resident,
    /// count in VmRSS and so in the memory budget, and are not reused by
    /// the large vectors that follow, which glibc maps on their own.
    void
    release_free_memory();

    /// @p bytes in the largest of B, KB, MB, GB that keeps it at or above
    /// one, with three significant digits ("1.69 GB").
    std::string
    format(double bytes);
  } // namespace MemoryUsage
} // namespace Fidus

#endif
