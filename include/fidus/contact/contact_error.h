#ifndef fidus_contact_contact_error_h
#define fidus_contact_contact_error_h

#include <stdexcept>
#include <string>

namespace Fidus::Contact
{
  /**
   * The exception thrown by the contact module for anything the caller can
   * cause: bad time step, non-finite velocities, overlapping input, size
   * mismatches, invalid walls. The message says what, where and what is
   * allowed, so that the time loop can report it as it is.
   */
  class ContactError : public std::runtime_error
  {
  public:
    /// Construct from a complete, human-readable message.
    explicit ContactError(const std::string &message)
      : std::runtime_error("fidus contact: " + message)
    {}
  };
} // namespace Fidus::Contact

#endif
