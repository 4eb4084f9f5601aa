#include <fidus/core/input_error.h>
#include <fidus/simulation/archive_reader.h>
#include <fidus/simulation/archive_writer.h>

namespace Fidus
{
  ArchiveReader::ArchiveReader(std::string content, const std::string &name)
    : bytes(std::move(content))
    , filename(name)
  {
    constexpr std::size_t trailer = 3 * sizeof(std::uint64_t);
    if (bytes.size() < trailer)
      fail("it is shorter than its trailer (truncated)");
    std::uint64_t size, sum, marker;
    const char   *t = bytes.data() + bytes.size() - trailer;
    std::memcpy(&size, t, 8);
    std::memcpy(&sum, t + 8, 8);
    std::memcpy(&marker, t + 16, 8);
    if (marker != ArchiveWriter::end_marker || size != bytes.size() - trailer)
      fail("its end marker or length is wrong (truncated or not a fidus "
           "checkpoint)");
    if (sum != ArchiveWriter::checksum(bytes.data(), size))
      fail("its checksum does not match (the file is damaged)");
    payload_size = size;
  }



  std::string
  ArchiveReader::get_string()
  {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > payload_size - position)
      fail("a string longer than the file");
    return std::string(take(n), n);
  }



  const char *
  ArchiveReader::take(const std::size_t n)
  {
    if (n > payload_size - position)
      fail("it ends before all of the state was read");
    const char *p = bytes.data() + position;
    position += n;
    return p;
  }



  void
  ArchiveReader::fail(const std::string &what) const
  {
    throw InputError("--resume: the checkpoint file '" + filename +
                     "' cannot be used: " + what +
                     "; allowed: a checkpoint written completely by fidus "
                     "(remove this checkpoint folder to resume from an "
                     "older one, or start the run anew)");
  }
} // namespace Fidus
