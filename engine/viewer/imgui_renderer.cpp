#include "viewer/imgui_renderer.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/rendering.h"
#include "gpu/shader_compiler.h"
#include "gpu/transfer.h"
#include "shared/viewer/imgui.h"

namespace avsm::viewer {

namespace {

static_assert(sizeof(ImDrawVert) == 20, "imgui.vert reads 5 floats per vertex");
static_assert(sizeof(ImDrawIdx) == 2, "indices are drawn as VK_INDEX_TYPE_UINT16");

// Host-visible buffers grow to the next power of two, so a panel that changes
// size every frame does not reallocate every frame.
void ensure_size(gpu::Context& ctx, gpu::Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                 const char* name) {
  if (buffer && buffer.size() >= bytes) return;
  const VkDeviceSize size = std::bit_ceil(std::max<VkDeviceSize>(bytes, 4096));
  buffer = gpu::Buffer::create(ctx, {size, usage, gpu::MemoryLocation::HostUpload, name});
}

ImTextureID id_of(size_t index) { return reinterpret_cast<ImTextureID>(index + 1); }
size_t index_of(ImTextureID id) { return reinterpret_cast<size_t>(id) - 1; }

}  // namespace

ImGuiRenderer::ImGuiRenderer(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, VkFormat target_format)
    : ctx_(ctx), sampler_(ctx, {.filter = VK_FILTER_LINEAR, .name = "imgui sampler"}) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = "imgui";
  desc.vertex = shaders.load("shaders/viewer/imgui.vert");
  desc.fragment = shaders.load("shaders/viewer/imgui.frag");
  desc.color_formats = {target_format};
  desc.blend = gpu::BlendMode::Alpha;
  pipeline_ = gpu::Pipeline::graphics(ctx, desc);
  upload_fonts();
}

void ImGuiRenderer::upload_fonts() {
  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  gpu::ImageDesc desc;
  desc.width = uint32_t(width);
  desc.height = uint32_t(height);
  desc.format = VK_FORMAT_R8G8B8A8_UNORM;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "imgui font atlas";
  font_atlas_ = gpu::Image::create(ctx_, desc);
  gpu::upload_image(ctx_, font_atlas_, pixels, VkDeviceSize(width) * height * 4,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  io.Fonts->SetTexID(add_texture(font_atlas_.view()));
}

ImTextureID ImGuiRenderer::add_texture(VkImageView view) {
  textures_.push_back(view);
  return id_of(textures_.size() - 1);
}

void ImGuiRenderer::replace_texture(ImTextureID id, VkImageView view) { textures_.at(index_of(id)) = view; }

void ImGuiRenderer::upload_geometry(const ImDrawData& data, Geometry& geometry) {
  ensure_size(ctx_, geometry.vertices, VkDeviceSize(data.TotalVtxCount) * sizeof(ImDrawVert),
              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "imgui vertices");
  ensure_size(ctx_, geometry.indices, VkDeviceSize(data.TotalIdxCount) * sizeof(ImDrawIdx), VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
              "imgui indices");
  auto* vertex_out = static_cast<ImDrawVert*>(geometry.vertices.mapped());
  auto* index_out = static_cast<ImDrawIdx*>(geometry.indices.mapped());
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    std::memcpy(vertex_out, list.VtxBuffer.Data, list.VtxBuffer.Size * sizeof(ImDrawVert));
    std::memcpy(index_out, list.IdxBuffer.Data, list.IdxBuffer.Size * sizeof(ImDrawIdx));
    vertex_out += list.VtxBuffer.Size;
    index_out += list.IdxBuffer.Size;
  }
}

void ImGuiRenderer::record(VkCommandBuffer cmd, const ImDrawData& data, VkImageView target, VkExtent2D extent,
                           uint32_t slot) {
  if (data.TotalVtxCount == 0 || extent.width == 0 || extent.height == 0) return;
  Geometry& geometry = geometry_.at(slot);
  upload_geometry(data, geometry);

  gpu::ColorTarget color{target};
  color.load = true;
  gpu::begin_rendering(cmd, extent, {&color, 1});
  pipeline_.bind(cmd);
  vkCmdBindIndexBuffer(cmd, geometry.indices.handle(), 0, VK_INDEX_TYPE_UINT16);
  shared::ImguiPush push{};
  push.scale = {2.0f / data.DisplaySize.x, 2.0f / data.DisplaySize.y};
  push.translate = {-1.0f - data.DisplayPos.x * push.scale.x, -1.0f - data.DisplayPos.y * push.scale.y};
  pipeline_.push_constants(cmd, push);

  // Clip rectangles are in display coordinates; the framebuffer may be scaled (HiDPI).
  const ImVec2 offset = data.DisplayPos, scale = data.FramebufferScale;
  ImTextureID bound = nullptr;
  uint32_t first_index = 0;
  int32_t first_vertex = 0;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    for (const ImDrawCmd& draw : list.CmdBuffer) {
      if (draw.UserCallback) {
        // ImGui's only built-in callback resets render state; ours never changes it.
        if (draw.UserCallback != ImDrawCallback_ResetRenderState) draw.UserCallback(&list, &draw);
        continue;
      }
      const float x0 = std::max((draw.ClipRect.x - offset.x) * scale.x, 0.0f);
      const float y0 = std::max((draw.ClipRect.y - offset.y) * scale.y, 0.0f);
      const float x1 = std::min((draw.ClipRect.z - offset.x) * scale.x, float(extent.width));
      const float y1 = std::min((draw.ClipRect.w - offset.y) * scale.y, float(extent.height));
      if (x1 <= x0 || y1 <= y0) continue;
      const VkRect2D scissor{{int32_t(x0), int32_t(y0)}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
      vkCmdSetScissor(cmd, 0, 1, &scissor);
      if (draw.TextureId != bound) {
        gpu::Bindings(ctx_, pipeline_)
            .buffer("Vertices", geometry.vertices)
            .image("panel_texture", textures_.at(index_of(draw.TextureId)), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   sampler_.handle())
            .push(cmd);
        bound = draw.TextureId;
      }
      vkCmdDrawIndexed(cmd, draw.ElemCount, 1, first_index + draw.IdxOffset, first_vertex + int32_t(draw.VtxOffset), 0);
    }
    first_index += uint32_t(list.IdxBuffer.Size);
    first_vertex += list.VtxBuffer.Size;
  }
  vkCmdEndRendering(cmd);
}

}  // namespace avsm::viewer
