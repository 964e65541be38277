#include "scene/binary_reader.h"

#include <fstream>
#include <system_error>

namespace avsm::scene::detail {

std::vector<std::byte> read_file_bytes(const std::filesystem::path& file, std::uint64_t max_bytes) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (error || !std::filesystem::exists(status)) throw LoadError(file, "file not found");
  if (!std::filesystem::is_regular_file(status)) throw LoadError(file, "not a regular file");
  const std::uint64_t size = std::filesystem::file_size(file, error);
  if (error) throw LoadError(file, "cannot read its size: " + error.message());
  if (size > max_bytes)
    throw LoadError(file, "file is " + std::to_string(size) + " bytes, more than the limit of " +
                              std::to_string(max_bytes));

  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw LoadError(file, "cannot open it for reading");
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  stream.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (static_cast<std::uint64_t>(stream.gcount()) != size)
    throw LoadError(file, "could only read " + std::to_string(stream.gcount()) + " of " +
                              std::to_string(size) + " bytes");
  return bytes;
}

}  // namespace avsm::scene::detail
