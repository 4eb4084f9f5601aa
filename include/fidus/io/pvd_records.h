#ifndef fidus_io_pvd_records_h
#define fidus_io_pvd_records_h

#include <string>
#include <utility>
#include <vector>

namespace Fidus
{
  /**
   * The entries (time, file) of a ParaView collection file (.pvd) written
   * by fidus whose file name carries a step number not above @p last_step.
   * A resumed run starts its collections from these, so that the rewritten
   * .pvd lists each output of the steps before the checkpoint once and
   * none of the steps after it (those are computed again). A missing file
   * gives no entries.
   */
  std::vector<std::pair<double, std::string>>
  read_pvd_records(const std::string &pvd_file, unsigned int last_step);

  /// The step number in an output file name such as particles-00012.vtp or
  /// solution_00012.pvtu: the last run of digits before the extension.
  long
  step_of_output_file(const std::string &file);
} // namespace Fidus

#endif
