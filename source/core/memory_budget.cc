#include <algorithm>
#include <fidus/core/memory_budget.h>
#include <fidus/core/memory_usage.h>
#include <fstream>
#include <limits>
#include <sstream>

namespace Fidus
{
  namespace
  {
    /// What a control group (cgroup v2) still lets this process's group
    /// allocate, in bytes; infinite without a limit.
    double
    control_group_room()
    {
      std::ifstream max("/sys/fs/cgroup/memory.max"),
        current("/sys/fs/cgroup/memory.current");
      std::string limit;
      double      used = 0.;
      if (!(max >> limit) || limit == "max" || !(current >> used))
        return std::numeric_limits<double>::infinity();
      std::istringstream value(limit);
      double             bytes = 0.;
      value >> bytes;
      return std::max(0., bytes - used);
    }

    /// What the machine can still give: MemAvailable, or less under a
    /// control group's limit; 0 when unknown.
    double
    machine_room()
    {
      return std::min(double(MemoryUsage::available_bytes()),
                      control_group_room());
    }
  } // namespace



  unsigned int
  ranks_on_this_machine(MPI_Comm comm)
  {
    MPI_Comm machine;
    MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
    int size = 1;
    MPI_Comm_size(machine, &size);
    MPI_Comm_free(&machine);
    return size;
  }



  MemoryBudget::MemoryBudget(const double limit_per_rank, MPI_Comm comm)
    : limit_per_rank(limit_per_rank)
    , ranks_on_machine(ranks_on_this_machine(comm))
  {}



  double
  MemoryBudget::free_bytes() const
  {
    if (limit_per_rank > 0.)
      return std::max(0.,
                      limit_per_rank - double(MemoryUsage::current_bytes()));
    const double room = machine_room();
    if (room == 0.)
      return std::numeric_limits<double>::infinity();
    // A tenth stays for what the step allocates besides the linear
    // system (the stress, the output, the mesh transfer).
    return 0.9 * room / ranks_on_machine;
  }



  void
  MemoryBudget::release_freed_memory_if_short(const double needed_bytes,
                                              MPI_Comm     comm) const
  {
    double least = free_bytes();
    MPI_Allreduce(MPI_IN_PLACE, &least, 1, MPI_DOUBLE, MPI_MIN, comm);
    if (least < 2. * needed_bytes)
      MemoryUsage::release_free_memory();
  }



  std::string
  MemoryBudget::source() const
  {
    if (limit_per_rank > 0.)
      return "'Fluid/Linear solver/Memory per rank' = " +
             MemoryUsage::format(limit_per_rank);
    std::ostringstream s;
    s << "nine tenths of the " << MemoryUsage::format(machine_room())
      << " this machine has available, shared by its " << ranks_on_machine
      << (ranks_on_machine == 1 ? " rank" : " ranks");
    return s.str();
  }
} // namespace Fidus
