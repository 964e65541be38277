#include "passes/shadows/inspection/shadow_debug_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <string>

#include "shared/passes/shadows/inspection/shadow_debug.h"

namespace avsm::passes {

ShadowDebugPass::ShadowDebugPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/inspection/shadow_debug.comp"), "shadow debug")) {}

void ShadowDebugPass::set_lights(const ShadowMaps& shadows) {
  images_.clear();
  drawn_revisions_.assign(shadows.light_count(), ~uint64_t(0));  // none drawn yet
  for (uint32_t light = 0; light < shadows.light_count(); ++light) {
    gpu::ImageDesc desc;
    // A paged map's picture is of its virtual map at kPagedPictureSize, through its pages.
    const uint32_t resolution = shadows.light_views()[light].resolution;
    desc.width = desc.height = shadows.is_paged(light) ? std::min(resolution, kPagedPictureSize) : resolution;
    desc.format = kFormat;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.name = "light " + std::to_string(light) + " debug image";
    images_.push_back(gpu::Image::create(ctx_, desc));
  }
}

void ShadowDebugPass::add_to_graph(rg::Graph& graph, const ShadowInputs& inputs, const ShadowMaps& maps) {
  for (uint32_t light = 0; light < images_.size(); ++light) {
    const uint64_t revision = maps.map_revision(light);
    if (revision == drawn_revisions_[light]) continue;
    drawn_revisions_[light] = revision;
    gpu::Image& image = images_[light];
    const std::string name = "light " + std::to_string(light) + " debug image";
    // Kept from frame to frame (read back, copied by the viewer): waits for the previous frame's readers.
    const rg::ImportState after_frame = rg::ImportState::of(rg::Usage::TransferSrc);
    rg::TextureHandle handle = rg::vulkan::import(graph, name, image, rewritten_after(after_frame), after_frame);
    struct Data {
      rg::TextureHandle image;
    };
    graph.add_pass<Data>(name, rg::QueueType::Compute,
        [&](rg::PassBuilder& b, Data& d) {
          d.image = b.write(handle, rg::Usage::StorageWrite);
          inputs.declare_reads(b);
        },
        [this, inputs, light](const Data& d, rg::PassContext& c) {
          pipeline_.bind(c.cmd());
          gpu::Bindings bindings(ctx_, pipeline_);
          bindings.image("debug_image", c.view(d.image), c.layout(d.image));
          inputs.bind(bindings, c);
          bindings.push(c.cmd());
          pipeline_.push_constants(c.cmd(), shared::ShadowDebugPush{light});
          const rg::TextureDesc& size = c.desc(d.image);
          pipeline_.dispatch_threads(c.cmd(), size.width, size.height);
        });
  }
}

}  // namespace avsm::passes
