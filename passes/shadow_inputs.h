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

#include "shared/shadow.h"

namespace rg {
class PassContext;
}
namespace avsm::gpu {
class Bindings;
}

namespace avsm::passes {

using shared::GpuShadow;  // shaders/shared/shadow.h
using shared::kMaxShadowedLights;
using shared::kNoReference;

// What a camera pass reads to look shadows up (shaders/common/shadow_lookup.glsl).
struct ShadowInputs {
  VkBuffer parameters = VK_NULL_HANDLE;  // one GpuShadow per scene light
  // The same buffer as a graph resource when the frame writes it (ShadowMaps uploads the
  // records in a "shadow parameters" pass); invalid for static parameters.
  rg::BufferHandle records;
  std::array<rg::BufferHandle, kMaxShadowedLights> maps{};
  std::array<rg::TextureHandle, kMaxShadowedLights> heads{};
  std::array<rg::BufferHandle, kMaxShadowedLights> nodes{};
  VkBuffer unused_buffer = VK_NULL_HANDLE;  // bound to slots without a map or lists
  VkImageView unused_heads = VK_NULL_HANDLE;

  // Declares the reads in a camera pass's setup.
  void declare_reads(rg::PassBuilder& builder) const;
  // In the pass's execute step: the parameters, then the maps, the list heads and the
  // list nodes (each an array of kMaxShadowedLights), by their shader names.
  void bind(gpu::Bindings& bindings, const rg::PassContext& context) const;
};

}  // namespace avsm::passes
