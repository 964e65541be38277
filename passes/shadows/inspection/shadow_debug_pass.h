#pragma once
// Pictures of the lights' transmittance maps: per light, an RGBA8 image of the
// transmittance reaching the first opaque surface of each level-0 texel (grey 0
// dark .. 1 lit), from the same data the camera passes read (AVSM nodes or the
// exact lists): the shadows as the light sees them. A paged map's picture shows its
// virtual map at kPagedPictureSize through the finest resident pages, tinted by their
// level with page edges drawn: which pages the receivers made resident.
// Shader: shaders/passes/shadows/inspection/shadow_debug.comp.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/shadow_maps.h"

namespace avsm::passes {

class ShadowDebugPass {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;
  static constexpr VkImageLayout kOutputLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  static constexpr uint32_t kPagedPictureSize = 1024;

  ShadowDebugPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // One image per light of `shadows`, at its map resolution.
  void set_lights(const ShadowMaps& shadows);
  // Adds "light <i> debug image" for every light whose maps changed since its picture
  // was drawn (ShadowMaps::map_revision(): a paged map that built nothing keeps its
  // picture); images in kOutputLayout after the frame.
  void add_to_graph(rg::Graph& graph, const ShadowInputs& inputs, const ShadowMaps& maps);
  const std::vector<gpu::Image>& images() const { return images_; }

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  std::vector<gpu::Image> images_;
  std::vector<uint64_t> drawn_revisions_;  // per light: the map revision its picture shows
};

}  // namespace avsm::passes
