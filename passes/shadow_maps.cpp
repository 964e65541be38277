#include "passes/shadow_maps.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/transfer.h"
#include "passes/hair_bins_pass.h"
#include "passes/light_depth_pass.h"
#include "passes/techniques/techniques.h"
#include "shared/hair_bins.h"

namespace avsm::passes {
namespace {

uint32_t filter_code(scene::ShadowFilter filter) {
  switch (filter) {
    case scene::ShadowFilter::point: return shared::kFilterPoint;
    case scene::ShadowFilter::bilinear: return shared::kFilterBilinear;
    case scene::ShadowFilter::trilinear: return shared::kFilterTrilinear;
  }
  return shared::kFilterBilinear;
}

// The settings every technique shares, then the technique's own (passes/techniques/).
void check_settings(const scene::Light& light, size_t index) {
  const std::string who = "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
  const scene::ShadowSettings& s = light.shadow;
  if (s.nodes < 4 || s.nodes > 16 || s.nodes % 4 != 0)
    throw std::invalid_argument(who + ": " + std::to_string(s.nodes) + " AVSM nodes; use 4, 8, 12 or 16");
  if (s.resolution < 1 || s.resolution > 16384)
    throw std::invalid_argument(who + ": shadow resolution " + std::to_string(s.resolution) + " is outside 1..16384");
  check_shadow_settings(s, who);
}

uint64_t round_up(uint64_t value, uint64_t multiple) { return (value + multiple - 1) / multiple * multiple; }

}  // namespace

void ShadowInputs::declare_reads(rg::PassBuilder& builder) const {
  if (records.valid()) builder.read(records, rg::Usage::StorageRead);
  for (uint32_t slot = 0; slot < kMaxShadowedLights; ++slot) {
    if (maps[slot].valid()) builder.read(maps[slot], rg::Usage::StorageRead);
    if (heads[slot].valid()) builder.read(heads[slot], rg::Usage::StorageRead);
    if (nodes[slot].valid()) builder.read(nodes[slot], rg::Usage::StorageRead);
  }
}

void ShadowInputs::bind(gpu::Bindings& bindings, const rg::PassContext& context) const {
  std::array<gpu::BufferRange, kMaxShadowedLights> map_buffers, node_buffers;
  std::array<VkImageView, kMaxShadowedLights> head_views;
  std::array<VkImageLayout, kMaxShadowedLights> head_layouts;
  for (uint32_t slot = 0; slot < kMaxShadowedLights; ++slot) {
    map_buffers[slot] = maps[slot].valid() ? context.buffer(maps[slot]) : gpu::BufferRange(unused_buffer);
    node_buffers[slot] = nodes[slot].valid() ? context.buffer(nodes[slot]) : gpu::BufferRange(unused_buffer);
    head_views[slot] = heads[slot].valid() ? context.view(heads[slot]) : unused_heads;
    head_layouts[slot] = heads[slot].valid() ? context.layout(heads[slot]) : VK_IMAGE_LAYOUT_GENERAL;
  }
  bindings.buffer("ShadowParameters", records.valid() ? context.buffer(records) : gpu::BufferRange(parameters))
      .buffer_array("AvsmMap", map_buffers)
      .image_array("shadow_list_heads", head_views, head_layouts)
      .buffer_array("ShadowListNodes", node_buffers);
}

UnshadowedInputs::UnshadowedInputs(gpu::Context& ctx) {
  parameters_ = gpu::create_buffer_from(ctx, std::vector<GpuShadow>(kMaxLights, GpuShadow{}),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "unshadowed parameters");
  gpu::ImageDesc desc;
  desc.format = kCaptureHeadFormat;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "unused list heads";
  heads_ = gpu::Image::create(ctx, desc);
  const uint32_t end_of_list = ~0u;
  gpu::upload_image(ctx, heads_, &end_of_list, sizeof(end_of_list), VK_IMAGE_LAYOUT_GENERAL);
}

ShadowInputs UnshadowedInputs::inputs() const {
  ShadowInputs inputs;
  inputs.parameters = parameters_.handle();
  inputs.unused_buffer = parameters_.handle();
  inputs.unused_heads = heads_.view();
  return inputs;
}

ShadowMaps::ShadowMaps(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      capture_opaque_(ctx, shaders),
      capture_hair_(ctx, shaders),
      capture_smoke_(ctx, shaders),
      sort_(ctx, shaders),
      unshadowed_(ctx) {
  for (const ShadowTechnique* technique : shadow_techniques())
    builders_.push_back(technique->create_builder(ctx, shaders));
}

void ShadowMaps::set_scene(const scene::Scene& scene, const ShadowOptions& options) {
  if (scene.lights.size() > kMaxShadowedLights)
    throw std::invalid_argument(scene.file.string() + ": " + std::to_string(scene.lights.size()) +
                                " lights; at most " + std::to_string(kMaxShadowedLights) + " can cast shadows");
  try {
    set_lights(scene.lights, scene.bounds, options);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(scene.file.string() + ": " + e.what());
  }
}

void ShadowMaps::set_lights(const std::vector<scene::Light>& lights, const scene::Bounds& casters,
                            const ShadowOptions& options) {
  if (lights.size() > kMaxShadowedLights)
    throw std::invalid_argument(std::to_string(lights.size()) + " lights; at most " +
                                std::to_string(kMaxShadowedLights) + " can cast shadows");
  for (size_t i = 0; i < lights.size(); ++i) check_settings(lights[i], i);
  options_ = options;
  views_.clear();
  lights_.clear();
  stats_.clear();
  for (size_t i = 0; i < lights.size(); ++i) {
    const scene::Light& light = lights[i];
    const uint32_t resolution = uint32_t(light.shadow.resolution);
    views_.push_back(make_light_view(light, casters, resolution));
    LightState state;
    state.settings = light.shadow;
    state.technique = &shadow_technique(light.shadow.technique);
    state.map_state.layout.resolution = resolution;
    state.map_state.layout.nodes = uint32_t(light.shadow.nodes);
    // Techniques without mips look trilinear up as bilinear.
    state.map_state.layout.levels = state.technique->mip_levels(light.shadow, resolution);
    state.technique->prepare(state.map_state);
    const std::string name = "light " + std::to_string(i);
    state.counter = gpu::Buffer::create(ctx_, {16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                               gpu::MemoryLocation::HostReadback, name + " capture counter"});
    if (light.shadow.build == scene::ShadowBuild::fixed)
      state.fixed_counter = gpu::Buffer::create(
          ctx_, {16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                 gpu::MemoryLocation::HostReadback, name + " fixed build counter"});
    // A first guess of 8 segments per texel; finish_frame() grows it to what the scene needs.
    state.capacity = std::min<uint64_t>(uint64_t(resolution) * resolution * 8,
                                        options_.capture_limit_bytes / kCaptureSegmentBytes);
    lights_.push_back(std::move(state));
    create_map(uint32_t(i));
    LightShadowStats stats;
    stats.light = light.name.empty() ? name : light.name;
    stats_.push_back(stats);
  }
  const uint64_t entries = lights_.size() * (options_.keep_reference ? 2 : 1);
  parameters_ = gpu::Buffer::create(ctx_, {std::max<uint64_t>(entries, 1) * sizeof(GpuShadow),
                                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           gpu::MemoryLocation::DeviceLocal, "shadow parameters"});
}

void ShadowMaps::create_map(uint32_t light) {
  LightState& state = lights_[light];
  if (!state.technique->has_map()) {
    state.map = {};
    return;
  }
  // Transfer source too, so tests and tools can read a map back.
  state.map = gpu::Buffer::create(
      ctx_, {state.technique->map_bytes(state.settings, state.map_state),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
             gpu::MemoryLocation::DeviceLocal, "light " + std::to_string(light) + " " + state.settings.technique + " map"});
}

GpuShadow ShadowMaps::gpu_shadow(uint32_t light, const View& camera) const {
  const LightView& v = views_[light];
  const LightState& s = lights_[light];
  GpuShadow g{};
  g.light_from_world = v.light_from_world;
  g.depth_plane = v.depth_plane;
  // A camera pixel spans about 2 tan(fov/2) / height radians; tan(fov/2) = 1 / |P[1][1]|.
  const float radians_per_pixel = 2.0f / (std::abs(camera.projection[1][1]) * float(std::max(camera.height, 1u)));
  g.texel_camera = glm::vec4(v.texel_size_base, v.texel_size_per_depth, v.far_depth, radians_per_pixel);
  g.camera_position = glm::vec4(camera.camera_position, options_.normal_offset_texels);
  g.technique = s.technique->code();
  g.depth_range = glm::vec4(v.near_depth, v.far_depth, 0.0f, 0.0f);
  g.resolution = s.map_state.layout.resolution;
  g.mip_count = s.map_state.layout.levels;
  g.filter_mode = filter_code(s.settings.filter);
  g.exponential = options_.exponential_interpolation ? 1u : 0u;
  g.slot = light;
  g.reference = options_.keep_reference ? light_count() + light : kNoReference;
  s.technique->fill(g, s.settings, v);
  return g;
}

// "shadow parameters": the frame's GpuShadow records, written by the GPU in the frame
// (not through a mapped pointer while it is declared), so the camera passes' reads are
// ordered after the write like any other graph access.
rg::BufferHandle ShadowMaps::add_parameter_upload(rg::Graph& graph, const View& camera) const {
  std::vector<GpuShadow> records(parameters_.size() / sizeof(GpuShadow));
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    records[i] = gpu_shadow(i, camera);
    if (options_.keep_reference) {
      GpuShadow& reference = records[light_count() + i];
      reference = records[i];
      reference.technique = shadow_technique_code("uncompressed");
      reference.mip_count = 1;  // the lists have no mips: the exact curve at every level of detail
      reference.reference = kNoReference;
    }
  }
  rg::BufferHandle buffer = rg::vulkan::import(graph, "shadow parameters", parameters_, rg::ImportState::none(),
                                               rg::ImportState::of(rg::Usage::StorageRead));
  struct Data {
    rg::BufferHandle records;
  };
  return graph.add_pass<Data>("shadow parameters", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) { d.records = b.write(buffer, rg::Usage::TransferDst); },
      [records = std::move(records)](const Data& d, rg::PassContext& c) {
        // vkCmdUpdateBuffer takes at most 64 KiB: kMaxShadowedLights * 2 records are far less.
        vkCmdUpdateBuffer(c.cmd(), c.buffer(d.records), 0, records.size() * sizeof(GpuShadow), records.data());
      })
      .records;
}

ShadowInputs ShadowMaps::add_to_graph(rg::Graph& graph, const View& camera,
                                      const ShadowCasters& casters) {
  ShadowInputs inputs = unshadowed_inputs();
  if (lights_.empty()) return inputs;
  inputs.parameters = parameters_.handle();
  inputs.records = add_parameter_upload(graph, camera);
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    LightState& light = lights_[i];
    const LightView& view = views_[i];
    const std::string prefix = "light " + std::to_string(i);

    const bool fixed = light.settings.build == scene::ShadowBuild::fixed;
    const TechniqueBuilder& builder = *builders_[light.technique->code() - 1];
    // The fixed build needs no lists; they are still captured for lookups that read them
    // (the uncompressed reference).
    const bool lookups_read_lists = light.technique->reads_capture_lists() || options_.keep_reference;
    std::optional<CaptureLists> lists;
    light.captured_lists = !fixed || lookups_read_lists;
    light.hair_segments = casters.strands.segment_count;
    if (light.captured_lists) lists = add_capture_lists(graph, i, casters);
    if (lookups_read_lists) {
      inputs.heads[i] = lists->heads;
      inputs.nodes[i] = lists->nodes;
    }
    if (!light.technique->has_map()) continue;
    rg::BufferHandle map = rg::vulkan::import(graph, prefix + " " + light.settings.technique + " map", light.map,
                                              rg::ImportState::none(), map_state_after_frame());
    if (fixed) {
      rg::BufferHandle counter = rg::vulkan::import(graph, prefix + " fixed build counter", light.fixed_counter,
                                                    rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
      inputs.maps[i] = builder.add_fixed_to_graph(
          {graph, prefix, map, counter, view, light.settings, light.map_state, casters, options_.smoke_samples_per_segment});
    } else {
      inputs.maps[i] = builder.add_to_graph({graph, prefix, *lists, map, view, light.settings, light.map_state}, *lists);
    }
  }
  return inputs;
}

// Light `i`'s capture lists: cleared, every caster appended, sorted if its settings ask.
CaptureLists ShadowMaps::add_capture_lists(rg::Graph& graph, uint32_t i, const ShadowCasters& casters) const {
  const LightState& light = lights_[i];
  const LightView& view = views_[i];
  const std::string prefix = "light " + std::to_string(i);
  rg::BufferHandle counter = rg::vulkan::import(graph, prefix + " capture counter", light.counter,
                                                rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  CaptureLists lists = add_capture_clear_pass(graph, prefix, view.resolution, light.capacity, counter);
  lists = capture_opaque_.add_to_graph(graph, prefix, lists, view, casters.meshes);
  lists = capture_hair_.add_to_graph(graph, prefix, lists, view, casters.strands);
  lists = capture_smoke_.add_to_graph(graph, prefix, lists, view, casters.volumes, options_.smoke_samples_per_segment);
  if (light.settings.sort) lists = sort_.add_to_graph(graph, prefix, lists, view.resolution);
  return lists;
}

FixedBuildStats ShadowMaps::fixed_build_stats(const LightState& light) const {
  uint32_t counters[4] = {0, 0, 0, 0};  // kFixedCounter* (shared/hair_bins.h)
  std::memcpy(counters, light.fixed_counter.mapped(), sizeof(counters));
  const uint32_t resolution = light.map_state.layout.resolution;
  FixedBuildStats f;
  f.inserted_segments = counters[shared::kFixedCounterInserted];
  const uint64_t entry_bytes = HairBinsPass::entry_bytes(light.hair_segments, ctx_.info().max_storage_buffer_range);
  f.light_depth_bytes = LightDepthPass::bytes(resolution);
  f.hair_bin_capacity = light.hair_segments == 0 ? 0 : entry_bytes / sizeof(uint32_t);
  f.hair_bin_bytes = HairBinsPass::tile_bytes(resolution) + entry_bytes;
  f.hair_bin_requested = counters[shared::kFixedCounterBinEntries];
  f.tiles_walked = counters[shared::kFixedCounterTilesWalked];
  return f;
}

void ShadowMaps::finish_frame() {
  for (size_t i = 0; i < lights_.size(); ++i) {
    LightState& light = lights_[i];
    LightShadowStats& stats = stats_[i];
    uint32_t counters[2] = {0, 0};  // capture segments, what the technique's build asked for
    if (light.captured_lists) std::memcpy(counters, light.counter.mapped(), sizeof(counters));
    const uint32_t requested = counters[0];
    stats.technique = light.settings.technique;
    stats.nodes = light.map_state.layout.nodes;
    stats.resolution = light.map_state.layout.resolution;
    stats.mip_levels = light.map_state.layout.levels;
    stats.capture_capacity = light.capacity;
    stats.capture_requested = requested;
    const uint64_t texels = uint64_t(light.map_state.layout.resolution) * light.map_state.layout.resolution;
    stats.capture_bytes = light.captured_lists ? light.capacity * kCaptureSegmentBytes + texels * 4 : 0;
    stats.fixed_build.reset();
    if (light.settings.build == scene::ShadowBuild::fixed) stats.fixed_build = fixed_build_stats(light);
    stats.overflowed = requested > light.capacity;
    if (stats.overflowed) {
      const uint64_t limit = options_.capture_limit_bytes / kCaptureSegmentBytes;
      light.capacity = std::min(limit, round_up(requested + requested / 4, 1024));
    }
    stats.next_capture_capacity = light.capacity;
    stats.grew = stats.next_capture_capacity > stats.capture_capacity;
    if (light.technique->finish_frame(counters, light.map_state, stats)) {  // the frame completed: replace the map
      create_map(uint32_t(i));
      stats.grew = true;
    }
    stats.map_bytes = light.map ? light.map.size() : 0;  // after a pool growth: the new map
  }
}

}  // namespace avsm::passes
