// libFuzzer target: scene files parse into a description or throw LoadError.
#include "scene/description.h"
#include "scene/load_error.h"

#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    avsm::scene::parse_scene_description(std::string_view(reinterpret_cast<const char*>(data), size), "/fuzz/scene.json");
  } catch (const avsm::scene::LoadError&) {
  }
  return 0;
}
