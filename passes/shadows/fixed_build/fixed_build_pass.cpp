#include "passes/shadows/fixed_build/fixed_build_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "gpu/transfer.h"
#include "passes/shadows/techniques/avsm/avsm_variants.h"
#include "passes/camera/volumes/volume_pass.h"
#include "shared/hair_bins.h"
#include "shared/passes/shadows/fixed_build/fixed_build.h"

namespace avsm::passes {

FixedBuildPass::FixedBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader,
                               std::string name, bool per_node_count)
    : ctx_(ctx),
      name_(std::move(name)),
      per_node_count_(per_node_count),
      depth_(ctx, shaders),
      bins_(ctx, shaders),
      pipelines_(avsm_node_variants(ctx, shaders, shader, name_, per_node_count)),
      depth_sampler_(ctx, gpu::texel_sampler_desc("light depth")),
      placeholder_(gpu::create_buffer_from(ctx, std::vector<shared::GpuVolume>(1), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           "fixed build: no casters")) {
  empty_atlas_.create_empty(ctx);
}

rg::BufferHandle FixedBuildPass::add_to_graph(rg::Graph& graph, const std::string& prefix,
                                              const FixedBuildTarget& target, const LightView& light,
                                              const ShadowCasters& casters, uint32_t smoke_samples_per_segment) const {
  const VkBuffer none = placeholder_.handle();
  const VkDeviceSize none_size = placeholder_.size();
  StrandCasters hair = casters.strands;
  if (hair.empty()) hair = {none, none_size, none, none_size, none, none_size, 0};
  VolumeCasters volumes = casters.volumes;
  if (!volumes.empty() && !volumes.has_atlas())
    throw std::invalid_argument(prefix + ": the fixed build reads smoke from the density brick atlas, and the "
                                "volume casters have none (VolumeCasters::atlas); pass it, or build from lists");
  if (volumes.empty())
    volumes = {none, none, none, none_size, 0, empty_atlas_.view(), empty_atlas_.sampler(), none};
  FixedBuildInputs inputs{depth_.add_to_graph(graph, prefix, light, casters.meshes),
                          bins_.add_to_graph(graph, prefix, light, casters.strands, target.counter)};
  struct Data {
    FixedBuildInputs inputs;
    rg::BufferHandle map;
  };
  const gpu::Pipeline& pipeline = pipelines_.get(per_node_count_ ? target.technique_size : 0);
  const shared::FixedBuildPush push{light.light_from_world,
                                    light.depth_plane,
                                    glm::vec4(hair_ribbon_facing_point(light), light.far_depth),
                                    {light.texel_size_base, light.texel_size_per_depth},
                                    light.near_depth,
                                    shared::fixed_build_sizes(target.technique_size, smoke_samples_per_segment,
                                                              volumes.volume_count),
                                    light.resolution,
                                    hair.first_segment,
                                    hair.segment_count,
                                    volumes.volume_mask};
  return graph.add_pass<Data>(prefix + " " + name_, rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) {
        d.inputs.depth = b.read(inputs.depth, rg::Usage::Sampled);
        d.inputs.bins.tiles = b.read(inputs.bins.tiles, rg::Usage::StorageRead);
        d.inputs.bins.entries = b.read_write(inputs.bins.entries, rg::Usage::StorageReadWrite);  // ordered in place
        d.inputs.bins.counter = b.read_write(inputs.bins.counter, rg::Usage::StorageReadWrite);
        d.map = b.write(target.map, rg::Usage::StorageWrite);
      },
      [this, &pipeline, push, hair, volumes](const Data& d, rg::PassContext& c) {
        pipeline.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline);
        bind_volumes(bindings, volumes, /*with_atlas=*/true);
        bindings.buffer("Points", hair.points)
            .buffer("Segments", hair.segments)
            .buffer("Strands", hair.strands)
            .image("light_depth", c.view(d.inputs.depth), c.layout(d.inputs.depth), depth_sampler_.handle())
            .buffer("HairTiles", c.buffer(d.inputs.bins.tiles))
            .buffer("HairBinEntries", c.buffer(d.inputs.bins.entries))
            .buffer("FixedBuildCounter", c.buffer(d.inputs.bins.counter))
            .buffer("Map", c.buffer(d.map));
        bindings.push(c.cmd());
        pipeline.push_constants(c.cmd(), push);
        pipeline.dispatch_threads(c.cmd(), push.resolution, push.resolution);
      })
      .map;
}

}  // namespace avsm::passes
