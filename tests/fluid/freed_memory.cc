// MemoryBudget::release_freed_memory_if_short(), the rule by which the cut
// element hands the memory a solve has freed back to the operating system:
// 200 MB in blocks of 1 KB (the size of a sparsity pattern's scratch) are
// allocated and freed below a block that stays, so that the freed memory
// stays resident in the process (glibc trims only the top of its heap by
// itself). Then:
// - with a budget of 1 TB per rank and a need of 1 MB (room for twice the
//   need), the freed memory must be kept: this rank's resident memory may
//   fall by at most 20 of the 200 MB;
// - with a budget 1 MB above what the process holds and a need of 100 MB
//   (short), it must be handed back: the resident memory must fall by at
//   least 100 of the 200 MB.
// On 1 and 2 ranks (the decision is the ranks' together).

#include "../fidus_test.h"

#include <fidus/core/memory_budget.h>
#include <fidus/core/memory_usage.h>
#include <memory>
#include <vector>

using namespace FidusTest;

namespace
{
  /// Allocate @p bytes in blocks of 1 KB, each written to, and free them,
  /// keeping one block allocated after them.
  std::unique_ptr<char[]>
  free_below_a_kept_block(const std::size_t bytes)
  {
    std::vector<std::unique_ptr<char[]>> blocks(bytes / 1024);
    for (auto &block : blocks)
      {
        block.reset(new char[1024]);
        for (unsigned int i = 0; i < 1024; i += 64)
          block[i] = char(i);
      }
    std::unique_ptr<char[]> kept(new char[1024]);
    kept[0] = 1;
    blocks.clear();
    return kept;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                             megabyte = 1024. * 1024.;

  auto         kept   = free_below_a_kept_block(200 * 1024 * 1024);
  const double before = Fidus::MemoryUsage::current_bytes();
  Fidus::MemoryBudget(1e12, MPI_COMM_WORLD)
    .release_freed_memory_if_short(megabyte, MPI_COMM_WORLD);
  const double after_room = Fidus::MemoryUsage::current_bytes();
  check_range("MB of resident memory handed back with room for twice the "
              "need",
              (before - after_room) / megabyte,
              -1e9,
              20.);

  const Fidus::MemoryBudget short_budget(after_room + megabyte, MPI_COMM_WORLD);
  short_budget.release_freed_memory_if_short(100. * megabyte, MPI_COMM_WORLD);
  const double after_short = Fidus::MemoryUsage::current_bytes();
  check_range("MB of resident memory handed back when short",
              (after_room - after_short) / megabyte,
              100.,
              1e9);
  return exit_code();
}
