#include "viewer/light_map_textures.h"

#include <rendergraph/vulkan/pass_context.h>

#include <string>

#include "gpu/context.h"
#include "passes/shadows/inspection/shadow_debug_pass.h"

namespace avsm::viewer {

namespace {

bool same_size(const gpu::Image& a, const gpu::Image& b) {
  return a.desc().width == b.desc().width && a.desc().height == b.desc().height && a.desc().format == b.desc().format;
}

// The panel samples the textures in fragment shaders. Before a copy their contents are not
// needed (UNDEFINED), but the panel's last reads must finish first.
constexpr rg::ImportState kPanelRead{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
constexpr rg::ImportState kPanelReadDiscarded{kPanelRead.stages, kPanelRead.access, VK_IMAGE_LAYOUT_UNDEFINED};

}  // namespace

LightMapTextures::LightMapTextures(gpu::Context& ctx, gpu::TimestampMode timestamps)
    : ctx_(ctx), executor_(ctx, timestamps) {}

bool LightMapTextures::would_recreate(const std::vector<gpu::Image>& sources) const {
  bool recreate = textures_.size() != sources.size();
  for (size_t i = 0; !recreate && i < sources.size(); ++i) recreate = !same_size(textures_[i], sources[i]);
  return recreate;
}

bool LightMapTextures::match_sources(const std::vector<gpu::Image>& sources) {
  if (!would_recreate(sources)) return false;
  textures_.clear();
  for (size_t i = 0; i < sources.size(); ++i) {
    gpu::ImageDesc desc = sources[i].desc();
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.name = "panel light map " + std::to_string(i);
    textures_.push_back(gpu::Image::create(ctx_, desc));
  }
  return true;
}

// One copy pass per light in a graph of its own: the sources come in the state the frame
// graph leaves them in, the textures leave ready for the panel; the graph plans the layout
// transitions in between.
void LightMapTextures::add_copy_pass(rg::Graph& graph, const gpu::Image& source, const gpu::Image& texture,
                                     size_t index) {
  const rg::ImportState renderer_output = rg::ImportState::of(rg::Usage::TransferSrc);
  static_assert(passes::ShadowDebugPass::kOutputLayout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  const std::string light = std::to_string(index);
  const rg::TextureHandle src = rg::vulkan::import(graph, "light map " + light, source, renderer_output, renderer_output);
  const rg::TextureHandle dst =
      rg::vulkan::import(graph, "panel light map " + light, texture, kPanelReadDiscarded, kPanelRead);
  graph.add_pass("copy light map " + light, rg::QueueType::Transfer,
      [&](rg::PassBuilder& b) {
        b.read(src, rg::Usage::TransferSrc);
        b.write(dst, rg::Usage::TransferDst);
      },
      [src, dst](rg::PassContext& c) {
        const rg::TextureDesc& size = c.desc(src);
        VkImageCopy region{};
        region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.extent = {size.width, size.height, 1};
        vkCmdCopyImage(c.cmd(), c.image(src), c.layout(src), c.image(dst), c.layout(dst), 1, &region);
      });
}

bool LightMapTextures::record_copies(VkCommandBuffer cmd, const std::vector<gpu::Image>& sources) {
  const bool recreated = match_sources(sources);
  if (sources.empty()) return recreated;
  rg::Graph graph;
  for (size_t i = 0; i < sources.size(); ++i) add_copy_pass(graph, sources[i], textures_[i], i);
  executor_.record(graph, cmd);
  return recreated;
}

}  // namespace avsm::viewer
