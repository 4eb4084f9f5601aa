#ifndef fidus_core_input_error_h
#define fidus_core_input_error_h

#include <stdexcept>
#include <string>

namespace Fidus
{
  /**
   * An error the user caused with the input (parameter file, positions file,
   * command line). main() prints its message alone, without a stack trace, and
   * exits with a non-zero status. The message names the entry, the value and
   * what is allowed.
   */
  class InputError : public std::runtime_error
  {
  public:
    /// Create the error with the complete, user-facing message.
    explicit InputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * A numerical failure at run time (solver did not converge, NaN, overlap
   * beyond tolerance, particle left the box). Reported with a diagnostic;
   * output written so far is kept.
   */
  class RunError : public std::runtime_error
  {
  public:
    /// Create the error with the complete diagnostic message.
    explicit RunError(const std::string &message)
      : std::runtime_error(message)
    {}
  };
} // namespace Fidus

#endif
