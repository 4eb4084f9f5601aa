#ifndef fidus_simulation_archive_reader_h
#define fidus_simulation_archive_reader_h

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace Fidus
{
  /**
   * Reads back what ArchiveWriter wrote, in the same order. The constructor
   * checks the trailer (length and checksum), so a truncated or damaged file
   * is reported before anything is read from it; reading past the end is an
   * error too. Errors are InputError: a bad checkpoint is bad input to
   * 'fidus --resume'.
   */
  class ArchiveReader
  {
  public:
    /// Check and hold the content of @p filename (named in messages).
    ArchiveReader(std::string content, const std::string &filename);

    /// Read a trivially copyable value.
    template <typename T>
    T
    get()
    {
      static_assert(std::is_trivially_copyable_v<T>);
      T value;
      std::memcpy(&value, take(sizeof(T)), sizeof(T));
      return value;
    }

    /// Read a vector written by ArchiveWriter::put(std::vector).
    template <typename T>
    std::vector<T>
    get_vector()
    {
      static_assert(std::is_trivially_copyable_v<T>);
      const std::uint64_t n = get<std::uint64_t>();
      if (n > (bytes.size() - position) / (sizeof(T) > 0 ? sizeof(T) : 1))
        fail("a vector longer than the file");
      std::vector<T> values(n);
      if (n > 0)
        std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
      return values;
    }

    /// Read a string.
    std::string
    get_string();

    /// Whether every byte of the payload was read.
    bool
    at_end() const
    {
      return position == payload_size;
    }

  private:
    const char *
    take(std::size_t n);

    [[noreturn]] void
    fail(const std::string &what) const;

    std::string bytes;
    std::string filename;
    std::size_t payload_size = 0;
    std::size_t position     = 0;
  };
} // namespace Fidus

#endif
