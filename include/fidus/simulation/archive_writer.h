#ifndef fidus_simulation_archive_writer_h
#define fidus_simulation_archive_writer_h

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace Fidus
{
  /**
   * Builds the byte image of a checkpoint's state file: plain values,
   * vectors and strings appended in a fixed order, closed by a trailer (the
   * payload length and its FNV-1a 64-bit checksum) so that ArchiveReader can
   * tell a complete file from a truncated or damaged one. Values are stored
   * as their bytes: a checkpoint is read back on the same kind of machine
   * (same endianness and double format), which is what restart on a cluster
   * or a workstation needs, and what makes a resumed run bit-identical.
   */
  class ArchiveWriter
  {
  public:
    /// Append a trivially copyable value (number, bool, fixed array).
    template <typename T>
    void
    put(const T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      const char *p = reinterpret_cast<const char *>(&value);
      bytes.append(p, sizeof(T));
    }

    /// Append a vector of trivially copyable values, length first.
    template <typename T>
    void
    put(const std::vector<T> &values)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      put<std::uint64_t>(values.size());
      if (!values.empty())
        bytes.append(reinterpret_cast<const char *>(values.data()),
                     values.size() * sizeof(T));
    }

    /// Append a string, length first.
    void
    put(const std::string &text)
    {
      put<std::uint64_t>(text.size());
      bytes += text;
    }

    /// The payload followed by its trailer.
    std::string
    finish() const;

    /// FNV-1a 64-bit checksum of @p size bytes at @p data; continue from
    /// @p previous (the checksum of what came before) to checksum in chunks.
    static std::uint64_t
    checksum(const char   *data,
             std::size_t   size,
             std::uint64_t previous = 14695981039346656037ULL);

    /// Marker written at the very end of every archive.
    static constexpr std::uint64_t end_marker = 0x46494455534348ULL;

  private:
    std::string bytes;
  };
} // namespace Fidus

#endif
