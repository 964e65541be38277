#pragma once
// Draws Dear ImGui's output with the engine's own pipeline machinery: push
// descriptors, dynamic rendering, vertices pulled from a storage buffer
// (shaders/viewer/imgui.vert/.frag). Draws on top of whatever the target holds.
//
// Textures: the font atlas, plus images the panel shows with ImGui::Image (the
// lights' transmittance maps); register them with add_texture. Everything a frame
// draws must be in SHADER_READ_ONLY_OPTIMAL while it runs.
#include <imgui.h>
#include <vulkan/vulkan.h>

#include <array>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/frame/frames_in_flight.h"

namespace avsm::gpu {
class Context;
class ShaderLibrary;
}  // namespace avsm::gpu

namespace avsm::viewer {

class ImGuiRenderer {
 public:
  // ImGui's context must exist (its font atlas is uploaded now).
  ImGuiRenderer(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, VkFormat target_format);

  // A texture id for ImGui::Image; `view` must stay valid while ids are drawn.
  ImTextureID add_texture(VkImageView view);
  void replace_texture(ImTextureID id, VkImageView view);

  // Records the draw lists into `target` (COLOR_ATTACHMENT_OPTIMAL, contents kept), with
  // the vertex and index buffers of frame slot `slot`, whose previous frame completed.
  void record(VkCommandBuffer cmd, const ImDrawData& data, VkImageView target, VkExtent2D extent, uint32_t slot);

 private:
  void upload_fonts();
  struct Geometry {
    gpu::Buffer vertices, indices;  // host-visible, filled as the frame is recorded
  };
  void upload_geometry(const ImDrawData& data, Geometry& geometry);

  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler sampler_;
  gpu::Image font_atlas_;
  std::vector<VkImageView> textures_;  // ImTextureID n is textures_[n - 1]
  std::array<Geometry, passes::kMaxFramesInFlight> geometry_;  // per frame slot
};

}  // namespace avsm::viewer
