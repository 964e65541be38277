#pragma once
// What a camera pass needs to look the shadow maps up (shaders/common/shadow_lookup.glsl):
// the per-light parameter block and the frame-graph handles of the maps. Produced by
// ShadowMaps::add_to_graph (passes/shadow_maps.h); kept apart so that a pass which only
// reads shadows does not include the whole shadow pipeline.
#include <rendergraph/graph.h>
#include <vulkan/vulkan.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace rg {
class PassContext;
}
namespace avsm::gpu {
class Bindings;
}

namespace avsm::passes {

inline constexpr uint32_t kMaxShadowedLights = 4;  // AVSM_MAX_SHADOWED_LIGHTS in shadow_lookup.glsl

// std430, 160 bytes; mirrors struct GpuShadow in shaders/common/shadow_lookup.glsl.
struct GpuShadow {
  glm::mat4 light_from_world;
  glm::vec4 depth_plane;
  glm::vec4 texel_camera;     // x + y * depth: texel world size; z: far depth; w: camera radians per pixel
  glm::vec4 camera_position;  // w: receivers' normal offset in texels
  glm::vec4 depth_range;      // x, y: the light's caster depth range (osm, fom); z: osm/fom lookup bias
  uint32_t technique;         // 0 none, 1 avsm, 2 uncompressed, 3 osm, 4 fom, 5 dsm
  uint32_t node_count;
  uint32_t resolution;
  uint32_t mip_count;
  uint32_t filter_mode;       // 0 point, 1 bilinear, 2 trilinear
  uint32_t exponential;
  uint32_t slot;
  uint32_t reference;         // index of this light's exact-reference entry, or kNoReference
};
static_assert(sizeof(GpuShadow) == 160);
inline constexpr uint32_t kNoReference = ~0u;

// What a camera pass reads to look shadows up (bindings AVSM_SHADOW_BINDING .. +3).
struct ShadowInputs {
  VkBuffer parameters = VK_NULL_HANDLE;  // one GpuShadow per scene light
  std::array<rg::BufferHandle, kMaxShadowedLights> maps{};
  std::array<rg::TextureHandle, kMaxShadowedLights> heads{};
  std::array<rg::BufferHandle, kMaxShadowedLights> nodes{};
  VkBuffer unused_buffer = VK_NULL_HANDLE;  // bound to slots without a map or lists
  VkImageView unused_heads = VK_NULL_HANDLE;

  // Declares the reads in a camera pass's setup.
  void declare_reads(rg::PassBuilder& builder) const;
  // In the pass's execute step: the parameters at `first_binding`, then the maps, the
  // list heads and the list nodes (each an array of kMaxShadowedLights) at +1, +2, +3,
  // matching AVSM_SHADOW_BINDING = first_binding in the shader.
  void bind(gpu::Bindings& bindings, uint32_t first_binding, const rg::PassContext& context) const;
};

}  // namespace avsm::passes
