// OpenVDB file framing, as written by io::Archive::write (OpenVDB 10):
//   int64 magic 0x56444220; uint32 file version; uint32 library major, minor;
//   char has_grid_offsets; [char compressed, versions 220-221]; 36-char UUID;
//   file metadata: int32 count, then per entry string name, string type,
//     uint32 byte count, bytes;
//   int32 grid count, then per grid a descriptor: string unique name, string
//     type, string instance parent, int64 grid, block and end positions,
//     followed by the grid itself up to the end position.
// Strings are a uint32 length and that many bytes.
#include "scene/vdb_layout.h"

#include "scene/load_error.h"

#include <array>
#include <cstring>

namespace avsm::scene::detail {
namespace {

constexpr std::int64_t kMagic = 0x56444220;
constexpr std::uint32_t kOldestVersion = 218;  // OPENVDB_FILE_VERSION_BOOST_UUID: ASCII UUID
constexpr std::uint32_t kNewestVersion = 224;  // OPENVDB_FILE_VERSION_MULTIPASS_IO (OpenVDB 10)
constexpr std::uint32_t kMaxStringBytes = 1u << 20;

class FramingReader {
 public:
  FramingReader(std::istream& stream, std::uint64_t size, const std::filesystem::path& file)
      : stream_(stream), size_(size), file_(file) {}

  [[noreturn]] void fail(const std::string& problem) const { throw LoadError(file_, problem); }
  std::uint64_t position() const { return position_; }

  void read_raw(void* out, std::uint64_t bytes, const char* what) {
    if (bytes > size_ - position_)
      fail("file is truncated: " + std::string(what) + " at byte " + std::to_string(position_) + " needs " +
           std::to_string(bytes) + " bytes, " + std::to_string(size_ - position_) + " remain");
    stream_.read(static_cast<char*>(out), std::streamsize(bytes));
    if (std::uint64_t(stream_.gcount()) != bytes) fail(std::string("cannot read ") + what);
    position_ += bytes;
  }
  template <class T>
  T read(const char* what) {
    T value{};
    read_raw(&value, sizeof value, what);
    return value;
  }
  std::string read_string(const char* what) {
    const auto length = read<std::uint32_t>(what);
    if (length > kMaxStringBytes) fail(std::string(what) + " claims " + std::to_string(length) + " bytes");
    std::string text(length, '\0');
    read_raw(text.data(), length, what);
    return text;
  }
  void skip(std::uint64_t bytes, const char* what) { seek(position_ + bytes, what); }
  void seek(std::uint64_t offset, const char* what) {
    if (offset < position_) fail(std::string(what) + " points backwards");
    if (offset > size_)
      fail("file is truncated: " + std::string(what) + " ends at byte " + std::to_string(offset) + " but the file has " +
           std::to_string(size_) + " bytes");
    stream_.seekg(std::streamoff(offset));
    if (!stream_) fail(std::string("cannot seek to ") + what);
    position_ = offset;
  }

 private:
  std::istream& stream_;
  std::uint64_t size_;
  const std::filesystem::path& file_;
  std::uint64_t position_ = 0;
};

void read_header(FramingReader& in, VdbLayout& layout) {
  if (in.read<std::int64_t>("magic number") != kMagic) in.fail("not an OpenVDB file (no 'VDB ' magic number)");
  layout.file_version = in.read<std::uint32_t>("file version");
  if (layout.file_version < kOldestVersion || layout.file_version > kNewestVersion)
    in.fail("OpenVDB file format version " + std::to_string(layout.file_version) + " is not supported (" +
            std::to_string(kOldestVersion) + " to " + std::to_string(kNewestVersion) + ")");
  in.read<std::uint32_t>("library major version");
  in.read<std::uint32_t>("library minor version");
  if (in.read<char>("grid offsets flag") == 0)
    in.fail("written as a stream without grid offsets, which is not supported; resave it with io::File");
  if (layout.file_version >= 220 && layout.file_version < 222) in.read<char>("compression flag");
  std::array<char, 36> uuid{};
  in.read_raw(uuid.data(), uuid.size(), "UUID");
}

void skip_file_metadata(FramingReader& in) {
  const auto count = in.read<std::int32_t>("file metadata count");
  if (count < 0) in.fail("negative file metadata count");
  for (std::int32_t i = 0; i < count; ++i) {
    in.read_string("metadata name");
    in.read_string("metadata type");
    in.skip(in.read<std::uint32_t>("metadata size"), "metadata value");
  }
}

VdbGridRecord read_grid(FramingReader& in) {
  VdbGridRecord grid;
  grid.unique_name = in.read_string("grid name");
  grid.type = in.read_string("grid type");
  grid.instance_parent = in.read_string("grid instance parent");
  grid.grid_pos = in.read<std::uint64_t>("grid position");
  grid.block_pos = in.read<std::uint64_t>("grid block position");
  grid.end_pos = in.read<std::uint64_t>("grid end position");
  const std::string label = "grid '" + grid.unique_name + "'";
  if (grid.grid_pos != in.position() || grid.block_pos < grid.grid_pos || grid.end_pos < grid.block_pos)
    in.fail(label + " has inconsistent offsets (" + std::to_string(grid.grid_pos) + ", " +
            std::to_string(grid.block_pos) + ", " + std::to_string(grid.end_pos) + ")");
  in.seek(grid.end_pos, ("data of " + label).c_str());
  return grid;
}

}  // namespace

VdbLayout read_vdb_layout(std::istream& stream, std::uint64_t size, const std::filesystem::path& file) {
  FramingReader in(stream, size, file);
  VdbLayout layout;
  read_header(in, layout);
  skip_file_metadata(in);
  const auto grid_count = in.read<std::int32_t>("grid count");
  if (grid_count < 0) in.fail("negative grid count");
  for (std::int32_t i = 0; i < grid_count; ++i) layout.grids.push_back(read_grid(in));
  return layout;
}

}  // namespace avsm::scene::detail
