// WarningLog: the first max_repeats warnings of a kind are written in full,
// the last of them says that further ones are counted; later ones are only
// counted, and summary() gives their number and the largest value with its
// step. A rank that does not write counts all the same and prints nothing.

#include "../fidus_test.h"

#include <fidus/core/warning_log.h>
#include <sstream>

using namespace FidusTest;

namespace
{
  unsigned int
  count_lines(const std::string &text, const std::string &needle)
  {
    unsigned int       n = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      n += line.find(needle) != std::string::npos;
    return n;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  std::ostringstream out, silent;
  Fidus::WarningLog  log(out, true, 3), quiet(silent, false, 3);
  const double       values[] = {1., 5., 2., 4., 3.};
  for (unsigned int step = 1; step <= 5; ++step)
    for (Fidus::WarningLog *l : {&log, &quiet})
      {
        l->warn("rigidity",
                "step " + std::to_string(step),
                step,
                values[step - 1]);
        if (step <= 2)
          l->warn("contact",
                  "contact at step " + std::to_string(step),
                  step,
                  0.1);
      }
  log.summary();
  quiet.summary();
  const std::string text = out.str();

  check_range("rigidity warnings counted", log.count("rigidity"), 5, 5);
  check_range("contact warnings counted", log.count("contact"), 2, 2);
  check_range("unknown kind counted", log.count("none"), 0, 0);
  check_range("full rigidity lines",
              count_lines(text, "fidus: warning: step "),
              3,
              3);
  check_range("fourth and fifth not written",
              count_lines(text, "warning: step 4") +
                count_lines(text, "warning: step 5"),
              0,
              0);
  check_range("third line says the rest is counted",
              count_lines(text, "step 3 [3 such warnings (rigidity); further"),
              1,
              1);
  check_range("summary line for rigidity",
              count_lines(text,
                          "5 warnings (rigidity) in this run, 3 of them "
                          "written above; the largest value was 5 at step 2"),
              1,
              1);
  check_range("contact below the limit: full lines, no summary",
              count_lines(text, "contact at step") +
                10 * count_lines(text, "warnings (contact)"),
              2,
              2);
  check_range("non-writing rank counts", quiet.count("rigidity"), 5, 5);
  check_range("non-writing rank prints nothing", silent.str().size(), 0, 0);
  return exit_code();
}
