// libFuzzer target: parse_gltf on .gltf text or .glb bytes, with no access to
// other files and small budgets, must return or throw LoadError.
#include "scene/gltf.h"
#include "scene/load_error.h"

#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avsm::scene::GltfOptions options;
  options.allow_external_files = false;
  options.max_vertices = 1u << 20;
  options.max_texture_size = 1024;
  try {
    avsm::scene::parse_gltf({reinterpret_cast<const std::byte*>(data), size}, "/nonexistent/fuzz.gltf", options);
  } catch (const avsm::scene::LoadError&) {
  }
  return 0;
}
