#pragma once
// Internal: bounded reading of binary files. Every count that comes from a file
// is checked against the bytes that are really there *before* anything is
// allocated, so a corrupt header cannot make a loader allocate gigabytes.
#include "scene/load_error.h"

#include <glm/glm.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace avsm::scene::detail {

static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec4) == 16, "glm vectors are read as packed floats");
static_assert(std::endian::native == std::endian::little,
              "the binary loaders read little-endian files by copying bytes");

// Reads a whole regular file. Refuses devices, directories and anything larger
// than max_bytes, with a LoadError naming the file.
std::vector<std::byte> read_file_bytes(const std::filesystem::path& file, std::uint64_t max_bytes);

class ByteReader {
 public:
  ByteReader(std::span<const std::byte> bytes, std::filesystem::path file)
      : bytes_(bytes), file_(std::move(file)) {}

  std::size_t size() const { return bytes_.size(); }
  std::size_t position() const { return position_; }
  std::size_t remaining() const { return bytes_.size() - position_; }
  const std::filesystem::path& file() const { return file_; }

  [[noreturn]] void fail(const std::string& problem) const { throw LoadError(file_, problem); }

  void seek(std::uint64_t offset, std::string_view what) {
    if (offset > bytes_.size())
      fail(std::string(what) + " starts at byte " + std::to_string(offset) +
           ", past the end of the file (" + std::to_string(bytes_.size()) + " bytes)");
    position_ = static_cast<std::size_t>(offset);
  }

  template <class T>
  T read(std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>);
    require(1, sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }

  template <class T>
  std::vector<T> read_array(std::uint64_t count, std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>);
    require(count, sizeof(T), what);
    std::vector<T> values(static_cast<std::size_t>(count));
    if (count != 0) std::memcpy(values.data(), bytes_.data() + position_, count * sizeof(T));
    position_ += static_cast<std::size_t>(count * sizeof(T));
    return values;
  }

  // Steps over count elements of element_size bytes, failing as read_array
  // would if they are not all there (for arrays a loader checks but does not keep).
  void skip_array(std::uint64_t count, std::size_t element_size, std::string_view what) {
    require(count, element_size, what);
    position_ += static_cast<std::size_t>(count * element_size);
  }

 private:
  // Fails unless count elements of element_size bytes remain (overflow-safe).
  void require(std::uint64_t count, std::size_t element_size, std::string_view what) const {
    if (count > remaining() / element_size)
      fail("file is truncated: " + std::string(what) + " needs " + std::to_string(count) + " x " +
           std::to_string(element_size) + " bytes at byte " + std::to_string(position_) +
           ", but only " + std::to_string(remaining()) + " bytes remain");
  }

  std::span<const std::byte> bytes_;
  std::filesystem::path file_;
  std::size_t position_ = 0;
};

// Appends the bytes of a trivially copyable value (for the file writers).
template <class T>
void append_bytes(std::vector<std::byte>& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

}  // namespace avsm::scene::detail
