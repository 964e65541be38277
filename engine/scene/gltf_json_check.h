#pragma once
// Internal: type checks on the glTF JSON members the loader uses. tinygltf
// silently ignores a member of the wrong type (a "primitives" object instead
// of an array, a string where a number belongs) and carries on with defaults,
// which would load silently wrong content; this turns those into LoadErrors
// with the JSON path, like scene files.
#include <cstddef>
#include <filesystem>
#include <span>

namespace avsm::scene::detail {

// `bytes` is the whole .gltf or .glb; for GLB the JSON chunk is checked and
// malformed GLB framing is left to tinygltf to report.
void check_gltf_json_types(std::span<const std::byte> bytes, const std::filesystem::path& file);

}  // namespace avsm::scene::detail
