#include <fidus/simulation/archive_writer.h>

namespace Fidus
{
  std::uint64_t
  ArchiveWriter::checksum(const char         *data,
                          const std::size_t   size,
                          const std::uint64_t previous)
  {
    std::uint64_t h = previous;
    for (std::size_t i = 0; i < size; ++i)
      {
        h ^= static_cast<unsigned char>(data[i]);
        h *= 1099511628211ULL;
      }
    return h;
  }



  std::string
  ArchiveWriter::finish() const
  {
    ArchiveWriter trailer;
    trailer.put<std::uint64_t>(bytes.size());
    trailer.put<std::uint64_t>(checksum(bytes.data(), bytes.size()));
    trailer.put<std::uint64_t>(end_marker);
    return bytes + trailer.bytes;
  }
} // namespace Fidus
