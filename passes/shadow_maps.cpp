#include "passes/shadow_maps.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/transfer.h"

namespace avsm::passes {
namespace {

uint32_t technique_code(scene::ShadowTechnique technique) {
  switch (technique) {
    case scene::ShadowTechnique::avsm: return 1u;
    case scene::ShadowTechnique::uncompressed: return 2u;
    case scene::ShadowTechnique::osm: return 3u;
    case scene::ShadowTechnique::fom: return 4u;
    case scene::ShadowTechnique::dsm: return 5u;
  }
  return 0u;
}

// Deep shadow maps: map words before the node pool (dsm_build.comp), and the
// exact-curve nodes kept before compression.
uint64_t dsm_pool_base_words(uint32_t resolution) { return (4 + 2 * uint64_t(resolution) * resolution + 3) & ~3ull; }
constexpr uint32_t kDsmInputNodes = 16;

// Planes of an opacity shadow map (`slices`, default 32) or terms of a Fourier
// opacity map (`terms`, default 16); the AVSM node count otherwise.
uint32_t technique_count(const scene::ShadowSettings& s) {
  if (s.technique == scene::ShadowTechnique::osm) return uint32_t(s.parameter("slices", 32));
  if (s.technique == scene::ShadowTechnique::fom) return uint32_t(s.parameter("terms", 16));
  if (s.technique == scene::ShadowTechnique::dsm) return kDsmInputNodes;
  return uint32_t(s.nodes);
}

uint32_t filter_code(scene::ShadowFilter filter) {
  switch (filter) {
    case scene::ShadowFilter::point: return 0u;
    case scene::ShadowFilter::bilinear: return 1u;
    case scene::ShadowFilter::trilinear: return 2u;
  }
  return 1u;
}

void check_settings(const scene::Light& light, size_t index) {
  const std::string who = "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
  const scene::ShadowSettings& s = light.shadow;
  const double error = s.parameter("error", 0.01);
  if (s.technique == scene::ShadowTechnique::dsm && !(error > 0.0 && error < 1.0))
    throw std::invalid_argument(who + ": dsm parameter error = " + std::to_string(error) + "; use a value in (0, 1)");
  const double slices = s.parameter("slices", 32), terms = s.parameter("terms", 16);
  if (s.technique == scene::ShadowTechnique::osm && (slices < 4 || slices > 64 || std::fmod(slices, 4.0) != 0.0))
    throw std::invalid_argument(who + ": osm parameter slices = " + std::to_string(slices) +
                                "; use a multiple of 4 from 4 to 64");
  if (s.technique == scene::ShadowTechnique::fom && (terms < 2 || terms > 32 || std::fmod(terms, 2.0) != 0.0))
    throw std::invalid_argument(who + ": fom parameter terms = " + std::to_string(terms) +
                                "; use an even number from 2 to 32");
  if (s.nodes < 4 || s.nodes > 16 || s.nodes % 4 != 0)
    throw std::invalid_argument(who + ": " + std::to_string(s.nodes) + " AVSM nodes; use 4, 8, 12 or 16");
  if (s.resolution < 1 || s.resolution > 16384)
    throw std::invalid_argument(who + ": shadow resolution " + std::to_string(s.resolution) + " is outside 1..16384");
}

uint64_t round_up(uint64_t value, uint64_t multiple) { return (value + multiple - 1) / multiple * multiple; }

// "<prefix> dsm clear": zeroes the deep shadow map's pool counter before the build allocates from it.
rg::BufferHandle add_dsm_clear_pass(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map) {
  struct Data {
    rg::BufferHandle map;
  };
  return graph.add_pass<Data>(prefix + " dsm clear", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) { d.map = b.write(map, rg::Usage::TransferDst); },
      [](const Data& d, rg::PassContext& c) { vkCmdFillBuffer(c.cmd(), c.buffer(d.map), 0, 16, 0); })
      .map;
}

}  // namespace

void ShadowInputs::declare_reads(rg::PassBuilder& builder) const {
  for (uint32_t slot = 0; slot < kMaxShadowedLights; ++slot) {
    if (maps[slot].valid()) builder.read(maps[slot], rg::Usage::StorageRead);
    if (heads[slot].valid()) builder.read(heads[slot], rg::Usage::StorageRead);
    if (nodes[slot].valid()) builder.read(nodes[slot], rg::Usage::StorageRead);
  }
}

void ShadowInputs::bind(gpu::Bindings& bindings, uint32_t first_binding, const rg::PassContext& context) const {
  std::array<VkBuffer, kMaxShadowedLights> map_buffers, node_buffers;
  std::array<VkImageView, kMaxShadowedLights> head_views;
  std::array<VkImageLayout, kMaxShadowedLights> head_layouts;
  for (uint32_t slot = 0; slot < kMaxShadowedLights; ++slot) {
    map_buffers[slot] = maps[slot].valid() ? context.buffer(maps[slot]) : unused_buffer;
    node_buffers[slot] = nodes[slot].valid() ? context.buffer(nodes[slot]) : unused_buffer;
    head_views[slot] = heads[slot].valid() ? context.view(heads[slot]) : unused_heads;
    head_layouts[slot] = heads[slot].valid() ? context.layout(heads[slot]) : VK_IMAGE_LAYOUT_GENERAL;
  }
  bindings.buffer(first_binding, parameters)
      .buffer_array(first_binding + 1, map_buffers)
      .image_array(first_binding + 2, head_views, head_layouts)
      .buffer_array(first_binding + 3, node_buffers);
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
      resolve_(ctx, shaders),
      mips_(ctx, shaders),
      osm_build_(ctx, shaders, "shaders/passes/osm_build.comp", "osm build"),
      fom_build_(ctx, shaders, "shaders/passes/fom_build.comp", "fom build"),
      dsm_build_(ctx, shaders, "shaders/passes/dsm_build.comp", "dsm build"),
      unshadowed_(ctx) {}

void ShadowMaps::set_scene(const scene::Scene& scene, const ShadowOptions& options) {
  if (scene.lights.size() > kMaxShadowedLights)
    throw std::invalid_argument(scene.file.string() + ": " + std::to_string(scene.lights.size()) +
                                " lights; at most " + std::to_string(kMaxShadowedLights) + " can cast shadows");
  set_lights(scene.lights, scene.bounds, options);
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
    state.layout.resolution = resolution;
    state.layout.nodes = uint32_t(light.shadow.nodes);
    // Mips exist for AVSM only (trilinear falls back to bilinear for the other techniques).
    const bool avsm = light.shadow.technique == scene::ShadowTechnique::avsm;
    state.layout.levels = avsm && light.shadow.filter == scene::ShadowFilter::trilinear
                              ? AvsmMapLayout::full_mip_count(resolution)
                              : 1;
    const std::string name = "light " + std::to_string(i);
    state.counter = gpu::Buffer::create(ctx_, {16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                               gpu::MemoryLocation::HostReadback, name + " capture counter"});
    // A first guess of 8 segments per texel; finish_frame() grows it to what the scene needs.
    state.capacity = std::min<uint64_t>(uint64_t(resolution) * resolution * 8,
                                        options_.capture_limit_bytes / kCaptureSegmentBytes);
    // Deep shadow maps: a first guess of 8 nodes per texel for the pool; finish_frame() grows it.
    state.pool_nodes = uint64_t(resolution) * resolution * 8;
    lights_.push_back(std::move(state));
    create_map(uint32_t(i));
    LightShadowStats stats;
    stats.light = light.name.empty() ? name : light.name;
    stats_.push_back(stats);
  }
  const uint64_t entries = lights_.size() * (options_.keep_reference ? 2 : 1);
  parameters_ = gpu::Buffer::create(ctx_, {std::max<uint64_t>(entries, 1) * sizeof(GpuShadow),
                                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::HostUpload,
                                           "shadow parameters"});
}

void ShadowMaps::create_map(uint32_t light) {
  LightState& state = lights_[light];
  const scene::ShadowSettings& settings = state.settings;
  const uint64_t texels = uint64_t(state.layout.resolution) * state.layout.resolution;
  uint64_t bytes = 0;
  switch (settings.technique) {
    case scene::ShadowTechnique::uncompressed: state.map = {}; return;
    case scene::ShadowTechnique::avsm: bytes = state.layout.bytes(); break;
    case scene::ShadowTechnique::osm: bytes = texels * technique_count(settings) * 4; break;  // K planes
    case scene::ShadowTechnique::fom: bytes = texels * technique_count(settings) * 8; break;  // K (a, b) pairs
    case scene::ShadowTechnique::dsm: bytes = (dsm_pool_base_words(state.layout.resolution) + 2 * state.pool_nodes) * 4; break;
  }
  // Transfer source too, so tests and tools can read a map back.
  state.map = gpu::Buffer::create(
      ctx_, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
             gpu::MemoryLocation::DeviceLocal,
             "light " + std::to_string(light) + " " + std::string(scene::to_string(settings.technique)) + " map"});
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
  g.technique = technique_code(s.settings.technique);
  // Opacity and Fourier maps smear a surface's own blocker over a slice (1/K of the
  // range): receivers look up `depth_bias` slices in front of themselves (default 1).
  const bool sliced = s.settings.technique == scene::ShadowTechnique::osm || s.settings.technique == scene::ShadowTechnique::fom;
  const float slice = (v.far_depth - v.near_depth) / float(std::max(technique_count(s.settings), 1u));
  const float bias = sliced ? float(s.settings.parameter("depth_bias", 1.0)) * slice : 0.0f;
  g.depth_range = glm::vec4(v.near_depth, v.far_depth, bias, 0.0f);
  g.node_count = technique_count(s.settings);
  g.resolution = s.layout.resolution;
  g.mip_count = s.layout.levels;
  g.filter_mode = filter_code(s.settings.filter);
  g.exponential = options_.exponential_interpolation ? 1u : 0u;
  g.slot = light;
  g.reference = options_.keep_reference ? light_count() + light : kNoReference;
  return g;
}

ShadowInputs ShadowMaps::add_to_graph(rg::Graph& graph, rg::vulkan::Executor& executor, const View& camera,
                                      const ShadowCasters& casters) {
  ShadowInputs inputs = unshadowed_inputs();
  if (lights_.empty()) return inputs;
  inputs.parameters = parameters_.handle();
  auto* parameters = static_cast<GpuShadow*>(parameters_.mapped());
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    parameters[i] = gpu_shadow(i, camera);
    if (options_.keep_reference) {
      GpuShadow& reference = parameters[light_count() + i];
      reference = parameters[i];
      reference.technique = technique_code(scene::ShadowTechnique::uncompressed);
      reference.reference = kNoReference;
    }
    LightState& light = lights_[i];
    const LightView& view = views_[i];
    const std::string prefix = "light " + std::to_string(i);

    rg::BufferHandle counter = graph.import_buffer(prefix + " capture counter", {light.counter.size()},
                                                   rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
    executor.bind(counter, light.counter);
    CaptureLists lists = add_capture_clear_pass(graph, prefix, view.resolution, light.capacity, counter);
    lists = capture_opaque_.add_to_graph(graph, prefix, lists, view, casters.meshes);
    lists = capture_hair_.add_to_graph(graph, prefix, lists, view, casters.strands);
    lists = capture_smoke_.add_to_graph(graph, prefix, lists, view, casters.volumes, options_.smoke_samples_per_segment);
    if (light.settings.sort) lists = sort_.add_to_graph(graph, prefix, lists, view.resolution);

    if (light.settings.technique == scene::ShadowTechnique::uncompressed || options_.keep_reference) {
      inputs.heads[i] = lists.heads;
      inputs.nodes[i] = lists.nodes;
    }
    if (light.settings.technique == scene::ShadowTechnique::uncompressed) continue;
    const std::string technique(scene::to_string(light.settings.technique));
    rg::BufferHandle map = graph.import_buffer(prefix + " " + technique + " map", {light.map.size()},
                                               rg::ImportState::none(), map_state_after_frame());
    executor.bind(map, light.map);
    const MapBuildParameters build{view.resolution, technique_count(light.settings), view.near_depth, view.far_depth,
                                   float(light.settings.parameter("error", 0.01))};
    switch (light.settings.technique) {
      case scene::ShadowTechnique::osm: inputs.maps[i] = osm_build_.add_to_graph(graph, prefix, lists, map, build); break;
      case scene::ShadowTechnique::fom: inputs.maps[i] = fom_build_.add_to_graph(graph, prefix, lists, map, build); break;
      case scene::ShadowTechnique::dsm:
        map = add_dsm_clear_pass(graph, prefix, map);
        inputs.maps[i] = dsm_build_.add_to_graph(graph, prefix, lists, map, build, &lists.counter);
        break;
      default:
        map = resolve_.add_to_graph(graph, prefix, lists, map, light.layout, view.far_depth);
        inputs.maps[i] = mips_.add_to_graph(graph, prefix, map, light.layout);
    }
  }
  return inputs;
}

void ShadowMaps::finish_frame() {
  for (size_t i = 0; i < lights_.size(); ++i) {
    LightState& light = lights_[i];
    LightShadowStats& stats = stats_[i];
    uint32_t counters[2] = {0, 0};  // capture segments, deep shadow map pool nodes asked for
    std::memcpy(counters, light.counter.mapped(), sizeof(counters));
    const uint32_t requested = counters[0];
    stats.technique = light.settings.technique;
    stats.nodes = light.layout.nodes;
    stats.resolution = light.layout.resolution;
    stats.mip_levels = light.layout.levels;
    stats.capture_capacity = light.capacity;
    stats.capture_requested = requested;
    stats.capture_bytes = light.capacity * kCaptureSegmentBytes + uint64_t(light.layout.resolution) * light.layout.resolution * 4;
    stats.overflowed = requested > light.capacity;
    if (stats.overflowed) {
      const uint64_t limit = options_.capture_limit_bytes / kCaptureSegmentBytes;
      light.capacity = std::min(limit, round_up(requested + requested / 4, 1024));
    }
    stats.next_capture_capacity = light.capacity;
    stats.grew = stats.next_capture_capacity > stats.capture_capacity;
    if (light.settings.technique == scene::ShadowTechnique::dsm) {
      stats.pool_requested = counters[1];
      stats.pool_capacity = light.pool_nodes;
      stats.pool_overflowed = counters[1] > light.pool_nodes;
      if (stats.pool_overflowed) {  // the last frame completed: the map can be replaced now
        light.pool_nodes = round_up(counters[1] + counters[1] / 4, 1024);
        create_map(uint32_t(i));
        stats.grew = true;
      }
    }
    stats.map_bytes = light.map ? light.map.size() : 0;  // after a pool growth: the new map
  }
}

}  // namespace avsm::passes
