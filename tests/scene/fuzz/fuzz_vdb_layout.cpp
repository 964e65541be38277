// libFuzzer target: the framing check that stands between OpenVDB and a .vdb
// file must accept or throw LoadError, never crash, hang or over-allocate.
#include "scene/load_error.h"
#include "scene/vdb_layout.h"

#include <cstdint>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream stream(std::string(reinterpret_cast<const char*>(data), size));
  try {
    avsm::scene::detail::read_vdb_layout(stream, size, "fuzz.vdb");
  } catch (const avsm::scene::LoadError&) {
  }
  return 0;
}
