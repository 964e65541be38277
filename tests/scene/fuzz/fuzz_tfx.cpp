// libFuzzer target: parse_tfx must return a valid groom or throw LoadError, nothing else.
#include "scene/hair.h"
#include "scene/load_error.h"

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto groom = avsm::scene::parse_tfx({reinterpret_cast<const std::byte*>(data), size}, "fuzz.tfx");
    if (groom.strand_offsets.back() != groom.points.size()) std::abort();  // validate_groom's promise
  } catch (const avsm::scene::LoadError&) {
  }
  return 0;
}
