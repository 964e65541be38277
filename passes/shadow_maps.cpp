#include "passes/shadow_maps.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/device_limits.h"
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

std::string light_name(const scene::Light& light, size_t index) {
  return "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
}

}  // namespace

void check_light_settings(const scene::Light& light, size_t index) {
  const std::string who = light_name(light, index);
  const scene::ShadowSettings& s = light.shadow;
  if (s.cascades < 1 || s.cascades > 4)
    throw std::invalid_argument(who + ": " + std::to_string(s.cascades) + " cascades; use 1 to 4");
  if (s.cascades > 1 && light.type != scene::LightType::directional)
    throw std::invalid_argument(who + ": cascades split a directional light's view; set shadow.cascades to 1 for a " +
                                std::string(scene::to_string(light.type)) + " light");
  if (s.cascades > 1 && s.fit != scene::ShadowFit::view)
    throw std::invalid_argument(who + ": cascades follow the camera; set shadow.fit to \"view\"");
  if (s.clusters < 0 || s.clusters > int(shared::kMaxViewsPerLight))
    throw std::invalid_argument(who + ": " + std::to_string(s.clusters) + " clusters; use 0 (off) to " +
                                std::to_string(shared::kMaxViewsPerLight));
  if (s.clusters > 1 && (light.type == scene::LightType::point || s.cascades > 1))
    throw std::invalid_argument(who + ": clustered maps are for directional and spot lights without cascades; "
                                "set shadow.clusters to 0");
  if (s.nodes < 4 || s.nodes > 16 || s.nodes % 4 != 0)
    throw std::invalid_argument(who + ": " + std::to_string(s.nodes) + " AVSM nodes; use 4, 8, 12 or 16");
  if (s.kernel_radius < 1 || s.kernel_radius > int(shared::kMaxKernelRadius))
    throw std::invalid_argument(who + ": shadow kernel radius " + std::to_string(s.kernel_radius) + " texels; use 1 to " +
                                std::to_string(shared::kMaxKernelRadius));
  if (s.resolution < 1 || s.resolution > 16384)
    throw std::invalid_argument(who + ": shadow resolution " + std::to_string(s.resolution) + " is outside 1..16384");
  check_shadow_settings(s, who);
}

namespace {

uint64_t round_up(uint64_t value, uint64_t multiple) { return (value + multiple - 1) / multiple * multiple; }


// Maps start on this many bytes in the atlas: above every device's storage buffer offset
// alignment (the mips pass binds windows of a map at aligned offsets).
constexpr uint64_t kAtlasAlignment = 256;

using gpu::format_mib;

}  // namespace

void ShadowInputs::declare_reads(rg::PassBuilder& builder) const {
  if (records.valid()) builder.read(records, rg::Usage::StorageRead);
  for (rg::BufferHandle map : maps) builder.read(map, rg::Usage::StorageRead);
  for (rg::BufferHandle list : lists) builder.read(list, rg::Usage::StorageRead);
}

void ShadowInputs::bind(gpu::Bindings& bindings, const rg::PassContext& context) const {
  auto or_unused = [&](const gpu::BufferRange& range) { return range.buffer ? range : gpu::BufferRange(unused_buffer); };
  bindings.buffer("ShadowParameters", records.valid() ? context.buffer(records) : gpu::BufferRange(parameters))
      .buffer("ShadowMapAtlas", or_unused(atlas))
      .buffer("ShadowListHeads", or_unused(list_heads))
      .buffer("ShadowListNodes", or_unused(list_nodes));
}

UnshadowedInputs::UnshadowedInputs(gpu::Context& ctx) : ctx_(ctx) { reserve(64); }

void UnshadowedInputs::reserve(uint32_t lights) {
  const uint64_t count = std::max(lights, 64u);
  if (parameters_ && parameters_.size() >= count * sizeof(GpuShadow)) return;
  parameters_ = gpu::create_buffer_from(ctx_, std::vector<GpuShadow>(count, GpuShadow{}),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "unshadowed parameters");
}

ShadowInputs UnshadowedInputs::inputs() const {
  ShadowInputs inputs;
  inputs.parameters = parameters_.handle();
  inputs.unused_buffer = parameters_.handle();
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
  // The scene's "shadows" block, under what the caller set.
  ShadowOptions merged = options;
  if (merged.map_budget_bytes == 0) merged.map_budget_bytes = uint64_t(scene.shadows.budget_mib * double(1 << 20));
  merged.fit_budget = merged.fit_budget || scene.shadows.fit_budget;
  std::vector<scene::Light> lights = scene.lights;
  for (scene::Light& light : lights)
    if (light.shadow.clusters == 0 && light.type != scene::LightType::point && light.shadow.cascades == 1)
      light.shadow.clusters = scene.shadows.clusters;
  try {
    set_lights(lights, scene.bounds, merged, scene_caster_objects(scene));
  } catch (const ShadowBudgetError& e) {
    throw ShadowBudgetError(scene.file.string() + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(scene.file.string() + ": " + e.what());
  }
}

void ShadowMaps::set_lights(const std::vector<scene::Light>& lights, const scene::Bounds& casters,
                            const ShadowOptions& options, const std::vector<CasterObject>& objects) {
  for (size_t i = 0; i < lights.size(); ++i) check_light_settings(lights[i], i);
  if (options.smoke_samples_per_segment < 1 || options.smoke_samples_per_segment > 255)
    throw std::invalid_argument("smoke capture: " + std::to_string(options.smoke_samples_per_segment) +
                                " samples per segment; use 1 to 255");
  // Frames in flight may use the buffers replaced here, and what finish_frame() reads of
  // them is per map as they declared it: the host finishes them first (the viewer's
  // LiveRenderer does), and then this wait costs nothing. Lights that only move do not
  // come here (place_light).
  vkDeviceWaitIdle(ctx_.device());
  retired_ = {};
  options_ = options;
  casters_ = casters;
  objects_ = objects;
  views_.clear();
  lights_.clear();
  maps_.clear();
  stats_.clear();
  for (size_t i = 0; i < lights.size(); ++i) {
    LightState state;
    state.light = lights[i];
    state.technique = &shadow_technique(lights[i].shadow.technique);
    lights_.push_back(std::move(state));
  }
  // Records: one per light first (what light_transmittance(i) reads), then the maps of
  // lights with several.
  record_count_ = uint32_t(lights_.size());
  for (uint32_t i = 0; i < lights_.size(); ++i) add_light_maps(i, casters, objects);
  fit_to_budget();
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    views_.push_back(maps_[lights_[i].first_map].view);
    LightShadowStats stats;
    stats.light = lights_[i].light.name.empty() ? "light " + std::to_string(i) : lights_[i].light.name;
    stats_.push_back(stats);
  }
  create_atlas();
  create_list_buffers();
  // Views fitted to the camera as the last frame saw it, so that light_views() matches the
  // next frame's maps when nothing moves (the viewer inspects texels between frames).
  if (last_camera_) update_views(*last_camera_);
  unshadowed_.reserve(uint32_t(lights_.size()));
  const uint64_t entries = uint64_t(record_count_) * (options_.keep_reference ? 2 : 1);
  parameters_.create(ctx_, {std::max<uint64_t>(entries, 1) * sizeof(GpuShadow),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            gpu::MemoryLocation::DeviceLocal, "shadow parameters"});
}

void ShadowMaps::set_frames_in_flight(uint32_t count) {
  check_frames_in_flight(count);
  if (count == frames_in_flight()) return;
  vkDeviceWaitIdle(ctx_.device());  // frames in flight use the per-slot buffers replaced here
  retired_ = {};
  parameters_.set_frames(ctx_, count);
  for (MapState& map : maps_) create_frame_buffers(map);
}

// The counters a frame's passes write for finish_frame(), and what it declared, per slot.
void ShadowMaps::create_frame_buffers(MapState& map) const {
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  map.counter.set_frames(ctx_, frames_in_flight());
  map.counter.create(ctx_, {16, usage, gpu::MemoryLocation::HostReadback, map.prefix + " capture counter"});
  if (lights_[map.light].light.shadow.build == scene::ShadowBuild::fixed) {
    map.fixed_counter.set_frames(ctx_, frames_in_flight());
    map.fixed_counter.create(ctx_, {16, usage, gpu::MemoryLocation::HostReadback, map.prefix + " fixed build counter"});
  }
  map.declared.assign(frames_in_flight(), DeclaredMap{});
}

void ShadowMaps::place_light(uint32_t index, const glm::vec3& position, const glm::vec3& direction) {
  LightState& light = lights_.at(index);
  light.light.position = position;
  light.light.direction = direction;
  for (uint32_t m = light.first_map; m < light.first_map + light.map_count; ++m) maps_[m].view = initial_view(maps_[m]);
  // Maps fitted to the camera are fitted again by the next frame (update_views).
  views_[index] = maps_[light.first_map].view;
}

// A map's view before any camera is known (update_views() fits the camera's).
LightView ShadowMaps::initial_view(const MapState& map) const {
  const LightState& light = lights_[map.light];
  const uint32_t resolution = uint32_t(light.light.shadow.resolution);
  if (map.face >= 0) return make_point_face_view(light.light, uint32_t(map.face), casters_, resolution);
  return make_light_view(light.light, map.fit_bounds, resolution);
}

// A light's maps: one, six cube faces, a map per cascade or per caster cluster.
void ShadowMaps::add_light_maps(uint32_t index, const scene::Bounds& casters, const std::vector<CasterObject>& objects) {
  LightState& light = lights_[index];
  const scene::Light& l = light.light;
  const std::string name = "light " + std::to_string(index);
  // Each map's name, what it is fitted to, and (clusters) which casters it takes.
  std::vector<MapState> maps;
  auto add = [&](std::string prefix, const scene::Bounds& bounds) {
    MapState& map = maps.emplace_back();
    map.light = index;
    map.prefix = std::move(prefix);
    map.fit_bounds = bounds;
    return &map;
  };
  if (l.type == scene::LightType::point) {
    light.views = shared::kViewsCube;
    for (int face = 0; face < 6; ++face) add(name + " face " + std::to_string(face), casters)->face = face;
  } else if (l.shadow.cascades > 1) {
    light.views = shared::kViewsCascades;  // update_views() fits each to the camera
    for (int c = 0; c < l.shadow.cascades; ++c) add(name + " cascade " + std::to_string(c), casters);
  } else if (l.shadow.clusters > 1) {
    const std::vector<CasterCluster> clusters = cluster_casters(l, objects, uint32_t(l.shadow.clusters));
    if (clusters.size() > 1) {
      light.views = shared::kViewsClusters;
      for (size_t c = 0; c < clusters.size(); ++c)
        add(name + " cluster " + std::to_string(c), clusters[c].bounds)->objects = clusters[c].objects;
    }
  }
  if (maps.empty()) {
    light.views = shared::kViewsSingle;
    add(name, casters);
  }
  light.first_map = uint32_t(maps_.size());
  light.map_count = uint32_t(maps.size());
  for (MapState& map : maps) {
    map.record = light.views == shared::kViewsSingle ? index : record_count_++;
    map.map_state = initial_map_state(light);
    create_frame_buffers(map);
    map.lookups_read_lists = light.technique->reads_capture_lists() || options_.keep_reference;
    maps_.push_back(std::move(map));
    maps_.back().view = initial_view(maps_.back());
  }
}

// The maps' bytes against the budget: an error naming the lights, or (fit_budget) the
// largest lights' resolutions halved until everything fits.
uint64_t ShadowMaps::map_budget() const {
  const uint64_t range = ctx_.info().max_storage_buffer_range;
  return options_.map_budget_bytes == 0 ? range : std::min(options_.map_budget_bytes, range);
}

// A map's state before its first frame, at its light's (possibly lowered) resolution.
TechniqueMapState ShadowMaps::initial_map_state(const LightState& light) const {
  const uint32_t resolution = uint32_t(light.light.shadow.resolution);
  TechniqueMapState state;
  state.layout.resolution = resolution;
  state.layout.nodes = uint32_t(light.light.shadow.nodes);
  // Techniques without mips look trilinear up as bilinear.
  state.layout.levels = light.technique->mip_levels(light.light.shadow, resolution);
  light.technique->prepare(state);
  return state;
}

// What a map takes of the atlas: its bytes, aligned as the atlas places it (0: no map).
uint64_t ShadowMaps::atlas_bytes(const MapState& map) const {
  const LightState& light = lights_[map.light];
  if (!light.technique->has_map()) return 0;
  return round_up(light.technique->map_bytes(light.light.shadow, map.map_state), kAtlasAlignment);
}

uint64_t ShadowMaps::atlas_bytes_needed() const {
  uint64_t bytes = 0;
  for (const MapState& map : maps_) bytes += atlas_bytes(map);
  return bytes;
}

void ShadowMaps::fit_to_budget() {
  const uint64_t range = ctx_.info().max_storage_buffer_range;
  const uint64_t budget = map_budget();
  auto light_bytes = [&](const LightState& light) {
    uint64_t bytes = 0;
    for (uint32_t m = light.first_map; m < light.first_map + light.map_count; ++m) bytes += atlas_bytes(maps_[m]);
    return bytes;
  };
  auto total = [&] { return atlas_bytes_needed(); };
  while (total() > budget) {
    if (!options_.fit_budget) {
      std::string lights;
      for (size_t i = 0; i < lights_.size(); ++i)
        lights += (i ? ", " : "") + light_name(lights_[i].light, i) + " " + format_mib(light_bytes(lights_[i]));
      throw ShadowBudgetError("the shadow maps need " + format_mib(total()) + ", over the budget of " +
                              format_mib(budget) + (budget == range ? " (the device's storage buffer range)" : "") + ": " + lights +
                              "; lower their shadow.resolution or nodes, raise the budget (shadows.budget_mib) "
                              "or let it lower resolutions (shadows.fit_budget)");
    }
    // Halve the resolution of the light with the most bytes that can still go lower.
    LightState* largest = nullptr;
    for (LightState& light : lights_)
      if (light.light.shadow.resolution > 16 && light_bytes(light) > 0 && (!largest || light_bytes(light) > light_bytes(*largest)))
        largest = &light;
    if (!largest)
      throw ShadowBudgetError("the shadow maps need " + format_mib(total()) +
                              " at their smallest resolution, over the budget of " + format_mib(budget) +
                              "; raise the budget (shadows.budget_mib) or shadow fewer lights");
    if (largest->lowered_from == 0) largest->lowered_from = uint32_t(largest->light.shadow.resolution);
    largest->light.shadow.resolution /= 2;
    for (uint32_t m = largest->first_map; m < largest->first_map + largest->map_count; ++m) {
      MapState& map = maps_[m];
      map.map_state = initial_map_state(*largest);
      map.view = initial_view(map);
    }
  }
}

// One buffer for every map, each a region of it.
void ShadowMaps::create_atlas() {
  uint64_t offset = 0;
  for (MapState& map : maps_) {
    map.atlas_offset = offset;
    offset += atlas_bytes(map);
  }
  for (MapState& map : maps_) map.map = {};
  atlas_ = {};
  if (offset == 0) return;
  // Transfer source too, so tests and tools can read a map back.
  atlas_ = gpu::Buffer::create(
      ctx_, {offset, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
             gpu::MemoryLocation::DeviceLocal, "shadow map atlas", "the lights' shadow.resolution or nodes"});
  for (MapState& map : maps_) {
    const LightState& light = lights_[map.light];
    if (!light.technique->has_map()) continue;
    map.map = gpu::Buffer::region(atlas_, map.atlas_offset, light.technique->map_bytes(light.light.shadow, map.map_state),
                                  map.prefix + " " + light.light.shadow.technique + " map");
  }
}

// What sizes the looked-up lists, for a message when they do not fit: the resolution of
// every light whose lookups read its lists.
std::string ShadowMaps::list_readers() const {
  std::string lights;
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    const MapState& first = maps_[lights_[i].first_map];
    if (!first.lookups_read_lists) continue;
    lights += (lights.empty() ? "" : ", ") + light_name(lights_[i].light, i) + " " +
              std::to_string(first.map_state.layout.resolution) + "x" +
              std::to_string(first.map_state.layout.resolution) +
              (lights_[i].map_count > 1 ? " x" + std::to_string(lights_[i].map_count) + " maps" : "");
  }
  return "the shadow.resolution (--shadow-res) of the lights whose lookups read the exact lists (technique "
         "uncompressed, --compare-to): " + lights;
}

// The lists that lookups read (the exact reference), copied each frame into two buffers
// every record addresses by offset. Their node capacities share the device's storage
// buffer range, so each map's capture grows to its share at most.
void ShadowMaps::create_list_buffers() {
  uint32_t readers = 0;
  for (const MapState& map : maps_) readers += map.lookups_read_lists ? 1 : 0;
  const uint64_t share = readers == 0 ? options_.capture_limit_bytes
                                      : std::min<uint64_t>(options_.capture_limit_bytes,
                                                           ctx_.info().max_storage_buffer_range / readers);
  uint64_t heads = 0, nodes = 0;
  for (MapState& map : maps_) {
    const uint64_t texels = uint64_t(map.map_state.layout.resolution) * map.map_state.layout.resolution;
    const uint64_t limit = (map.lookups_read_lists ? share : options_.capture_limit_bytes) / kCaptureSegmentBytes;
    // A first guess of 8 segments per texel; finish_frame() grows it to what the scene needs.
    if (map.capacity == 0) map.capacity = texels * 8;
    map.capacity = std::min(map.capacity, limit);
    if (!map.lookups_read_lists) continue;
    map.list_heads_offset = heads;
    map.list_nodes_offset = nodes;
    heads += round_up(texels * sizeof(uint32_t), kAtlasAlignment);
    nodes += round_up(map.capacity * kCaptureSegmentBytes, kAtlasAlignment);
  }
  for (MapState& map : maps_) {
    map.list_heads = {};
    map.list_nodes = {};
  }
  list_heads_ = {};
  list_nodes_ = {};
  if (heads == 0) return;
  // TRANSFER_SRC: they can be read back (looked_up_list_heads/nodes), like the atlas.
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  const std::string sized_by = list_readers();
  constexpr gpu::MemoryLocation kDevice = gpu::MemoryLocation::DeviceLocal;
  list_heads_ = gpu::Buffer::create(ctx_, {heads, usage, kDevice, "looked-up list heads", sized_by});
  list_nodes_ = gpu::Buffer::create(ctx_, {nodes, usage, kDevice, "looked-up list nodes", sized_by});
  for (MapState& map : maps_) {
    if (!map.lookups_read_lists) continue;
    const uint64_t texels = uint64_t(map.map_state.layout.resolution) * map.map_state.layout.resolution;
    map.list_heads = gpu::Buffer::region(list_heads_, map.list_heads_offset, texels * sizeof(uint32_t), map.prefix + " looked-up list heads");
    map.list_nodes = gpu::Buffer::region(list_nodes_, map.list_nodes_offset, map.capacity * kCaptureSegmentBytes,
                                         map.prefix + " looked-up list nodes");
  }
}

// Maps fitted to the camera follow it: a directional light's (fit view) and its cascades.
void ShadowMaps::update_views(const View& camera) {
  last_camera_ = camera;
  for (LightState& light : lights_) {
    const scene::Light& l = light.light;
    if (l.type != scene::LightType::directional || l.shadow.fit != scene::ShadowFit::view) continue;
    if (light.views == shared::kViewsClusters) continue;  // fitted to their clusters
    const float far = l.shadow.distance > 0.0f ? std::min(l.shadow.distance, camera.far_plane) : camera.far_plane;
    const uint32_t resolution = uint32_t(l.shadow.resolution);
    if (light.views == shared::kViewsCascades) {
      light.cascade_ends = cascade_ends(camera.near_plane, far, light.map_count);
      float begin = camera.near_plane;
      for (uint32_t c = 0; c < light.map_count; ++c) {
        const float end = light.cascade_ends[c];
        maps_[light.first_map + c].view = make_fitted_directional_view(l, casters_, resolution, camera_slice(camera, begin, end));
        // The next cascade starts where this one's blend band does, so both cover the band.
        begin = end - (end - begin) * l.shadow.cascade_blend;
      }
    } else {
      maps_[light.first_map].view = make_fitted_directional_view(l, casters_, resolution, camera_slice(camera, camera.near_plane, far));
    }
  }
  for (uint32_t i = 0; i < lights_.size(); ++i) views_[i] = maps_[lights_[i].first_map].view;
}

std::vector<LightView> ShadowMaps::map_views(uint32_t light) const {
  std::vector<LightView> views;
  const LightState& l = lights_.at(light);
  for (uint32_t m = l.first_map; m < l.first_map + l.map_count; ++m) views.push_back(maps_[m].view);
  return views;
}

GpuShadow ShadowMaps::gpu_shadow(const MapState& map, const View& camera) const {
  const LightView& v = map.view;
  const LightState& light = lights_[map.light];
  const scene::ShadowSettings& settings = light.light.shadow;
  GpuShadow g{};
  g.light_from_world = v.light_from_world;
  g.depth_plane = v.depth_plane;
  // A camera pixel spans about 2 tan(fov/2) / height radians; tan(fov/2) = 1 / |P[1][1]|.
  const float radians_per_pixel = 2.0f / (std::abs(camera.projection[1][1]) * float(std::max(camera.height, 1u)));
  g.texel_camera = glm::vec4(v.texel_size_base, v.texel_size_per_depth, v.far_depth, radians_per_pixel);
  g.camera_position = glm::vec4(camera.camera_position, options_.normal_offset_texels);
  g.technique = light.technique->code();
  g.depth_range = glm::vec4(v.near_depth, v.far_depth, 0.0f, 0.0f);
  g.resolution = map.map_state.layout.resolution;
  g.mip_count = map.map_state.layout.levels;
  g.filter_mode = filter_code(settings.filter);
  g.kernel = settings.kernel == scene::ShadowKernel::box        ? shared::kKernelBox
             : settings.kernel == scene::ShadowKernel::gaussian ? shared::kKernelGaussian
                                                                : shared::kKernelNone;
  g.kernel_radius = uint32_t(settings.kernel_radius);
  g.exponential = options_.exponential_interpolation ? 1u : 0u;
  g.map_offset = uint32_t(map.atlas_offset / sizeof(glm::vec4));
  g.list_heads_offset = uint32_t(map.list_heads_offset / sizeof(uint32_t));
  g.list_nodes_offset = uint32_t(map.list_nodes_offset / kCaptureSegmentBytes);
  g.views = shared::kViewsSingle;
  g.reference = options_.keep_reference ? record_count_ + map.record : kNoReference;
  light.technique->fill(g, settings, v);
  return g;
}

// Every record of the frame: each map's, each multi-map light's (its first map's with how
// to find the others), then the exact references.
std::vector<GpuShadow> ShadowMaps::frame_records(const View& camera) const {
  std::vector<GpuShadow> records(uint64_t(record_count_) * (options_.keep_reference ? 2 : 1));
  for (const MapState& map : maps_) records[map.record] = gpu_shadow(map, camera);
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    const LightState& light = lights_[i];
    if (light.views == shared::kViewsSingle) continue;
    const MapState& first = maps_[light.first_map];
    GpuShadow& g = records[i];
    g = records[first.record];
    g.views = light.views;
    g.first_view = first.record;
    g.view_count = light.map_count;
    g.reference = options_.keep_reference ? record_count_ + i : kNoReference;
    if (light.views == shared::kViewsCube) g.view_select = glm::vec4(light.light.position, 0.0f);
    if (light.views == shared::kViewsCascades) {
      const glm::mat4 world_from_view = glm::inverse(camera.view);
      g.view_select = glm::vec4(-glm::normalize(glm::vec3(world_from_view[2])), light.light.shadow.cascade_blend);
      for (uint32_t c = 0; c < 4; ++c)
        g.cascade_ends[c] = c < light.cascade_ends.size() ? light.cascade_ends[c] : camera.far_plane;
    }
  }
  if (options_.keep_reference) {
    for (uint32_t r = 0; r < record_count_; ++r) {
      GpuShadow& reference = records[record_count_ + r];
      reference = records[r];
      reference.technique = shadow_technique_code("uncompressed");
      reference.mip_count = 1;  // the lists have no mips: the exact curve at every level of detail
      reference.reference = kNoReference;
      if (reference.views != shared::kViewsSingle) reference.first_view += record_count_;
    }
  }
  return records;
}

// "shadow parameters": the frame's GpuShadow records, written by the GPU in the frame
// (not through a mapped pointer while it is declared), so the camera passes' reads are
// ordered after the write like any other graph access.
// One block per frame slot: a frame in flight keeps reading its own while the next is written.
rg::BufferHandle ShadowMaps::add_parameter_upload(rg::Graph& graph, const View& camera, uint32_t slot) const {
  std::vector<GpuShadow> records = frame_records(camera);
  rg::BufferHandle buffer = rg::vulkan::import(graph, "shadow parameters", parameters_[slot], rg::ImportState::none(),
                                               rg::ImportState::of(rg::Usage::StorageRead));
  struct Data {
    rg::BufferHandle records;
  };
  return graph.add_pass<Data>("shadow parameters", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) { d.records = b.write(buffer, rg::Usage::TransferDst); },
      [records = std::move(records)](const Data& d, rg::PassContext& c) {
        // vkCmdUpdateBuffer takes at most 64 KiB a call.
        constexpr size_t kPerCall = (64 << 10) / sizeof(GpuShadow);
        const gpu::BufferRange target = c.buffer(d.records);
        for (size_t first = 0; first < records.size(); first += kPerCall) {
          const size_t count = std::min(kPerCall, records.size() - first);
          vkCmdUpdateBuffer(c.cmd(), target, target.offset + first * sizeof(GpuShadow), count * sizeof(GpuShadow),
                            records.data() + first);
        }
      })
      .records;
}

ShadowInputs ShadowMaps::add_to_graph(rg::Graph& graph, const View& camera, const ShadowCasters& casters,
                                      uint32_t slot) {
  if (slot >= frames_in_flight())
    throw std::invalid_argument("ShadowMaps: frame slot " + std::to_string(slot) + " of " +
                                std::to_string(frames_in_flight()) + " frames in flight");
  retired_.declared(slot);
  ShadowInputs inputs = unshadowed_inputs();
  inputs.frame_slot = slot;
  if (lights_.empty()) return inputs;
  update_views(camera);
  inputs.parameters = parameters_[slot].handle();
  inputs.records = add_parameter_upload(graph, camera, slot);
  inputs.atlas = atlas_ ? gpu::BufferRange(atlas_) : gpu::BufferRange();
  inputs.list_heads = list_heads_ ? gpu::BufferRange(list_heads_) : gpu::BufferRange();
  inputs.list_nodes = list_nodes_ ? gpu::BufferRange(list_nodes_) : gpu::BufferRange();
  for (MapState& map : maps_) {
    const LightState& light = lights_[map.light];
    const scene::ShadowSettings& settings = light.light.shadow;
    const ShadowCasters map_casters = casters_of(map, casters);
    const bool fixed = settings.build == scene::ShadowBuild::fixed;
    const TechniqueBuilder& builder = *builders_[light.technique->code() - 1];
    // The fixed build needs no lists; they are still captured for lookups that read them
    // (the uncompressed reference).
    std::optional<CaptureLists> lists;
    DeclaredMap& declared = map.declared[slot];
    declared = {map.capacity, map.map_state, !fixed || map.lookups_read_lists, map_casters.strands.segment_count};
    if (declared.captured_lists) lists = add_capture_lists(graph, map, map_casters, slot);
    if (map.lookups_read_lists) add_list_copy(graph, map, *lists, inputs);
    if (!light.technique->has_map()) continue;
    // The map persists from frame to frame: this frame's build waits for the previous one's lookups.
    rg::BufferHandle handle = rg::vulkan::import(graph, map.prefix + " " + settings.technique + " map", map.map,
                                                 rewritten_after(map_state_after_frame()), map_state_after_frame());
    if (fixed) {
      rg::BufferHandle counter = rg::vulkan::import(graph, map.prefix + " fixed build counter", map.fixed_counter[slot],
                                                    rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
      inputs.maps.push_back(builder.add_fixed_to_graph({graph, map.prefix, handle, counter, map.view, settings,
                                                        map.map_state, map_casters, options_.smoke_samples_per_segment}));
    } else {
      inputs.maps.push_back(
          builder.add_to_graph({graph, map.prefix, *lists, handle, map.view, settings, map.map_state}, *lists));
    }
  }
  return inputs;
}

// A map's capture lists: cleared, every caster appended, sorted if its settings ask.
CaptureLists ShadowMaps::add_capture_lists(rg::Graph& graph, const MapState& map, const ShadowCasters& casters,
                                           uint32_t slot) const {
  const scene::ShadowSettings& settings = lights_[map.light].light.shadow;
  const LightView& view = map.view;
  rg::BufferHandle counter = rg::vulkan::import(graph, map.prefix + " capture counter", map.counter[slot],
                                                rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  CaptureLists lists = add_capture_clear_pass(graph, map.prefix, view.resolution, map.capacity, counter);
  lists = capture_opaque_.add_to_graph(graph, map.prefix, lists, view, casters.meshes);
  lists = capture_hair_.add_to_graph(graph, map.prefix, lists, view, casters.strands);
  lists = capture_smoke_.add_to_graph(graph, map.prefix, lists, view, casters.volumes, options_.smoke_samples_per_segment);
  if (settings.sort) lists = sort_.add_to_graph(graph, map.prefix, lists, view.resolution);
  return lists;
}

// "<map> copy lists": the heads and nodes into the map's regions of the looked-up list
// buffers, which every camera pass binds whole.
void ShadowMaps::add_list_copy(rg::Graph& graph, const MapState& map, const CaptureLists& lists,
                               ShadowInputs& inputs) const {
  const rg::ImportState after = rg::ImportState::of(rg::Usage::StorageRead);
  rg::BufferHandle heads = rg::vulkan::import(graph, map.prefix + " looked-up list heads", map.list_heads,
                                              rewritten_after(after), after);
  rg::BufferHandle nodes = rg::vulkan::import(graph, map.prefix + " looked-up list nodes", map.list_nodes,
                                              rewritten_after(after), after);
  struct Data {
    rg::TextureHandle source_heads;
    rg::BufferHandle source_nodes, heads, nodes;
  };
  const uint32_t resolution = map.view.resolution;
  const uint64_t node_bytes = map.capacity * kCaptureSegmentBytes;
  const Data& copy = graph.add_pass<Data>(map.prefix + " copy lists", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b, Data& d) {
        d.source_heads = b.read(lists.heads, rg::Usage::TransferSrc);
        d.source_nodes = b.read(lists.nodes, rg::Usage::TransferSrc);
        d.heads = b.write(heads, rg::Usage::TransferDst);
        d.nodes = b.write(nodes, rg::Usage::TransferDst);
      },
      [resolution, node_bytes](const Data& d, rg::PassContext& c) {
        const gpu::BufferRange heads = c.buffer(d.heads), nodes = c.buffer(d.nodes), source = c.buffer(d.source_nodes);
        VkBufferImageCopy image_copy{};
        image_copy.bufferOffset = heads.offset;
        image_copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        image_copy.imageExtent = {resolution, resolution, 1};
        vkCmdCopyImageToBuffer(c.cmd(), c.image(d.source_heads), c.layout(d.source_heads), heads, 1, &image_copy);
        const VkBufferCopy node_copy{source.offset, nodes.offset, node_bytes};
        vkCmdCopyBuffer(c.cmd(), source, nodes, 1, &node_copy);
      });
  inputs.lists.push_back(copy.heads);
  inputs.lists.push_back(copy.nodes);
}

// The casters a map takes: all of them, or its cluster's.
ShadowCasters ShadowMaps::casters_of(const MapState& map, const ShadowCasters& all) const {
  if (!map.objects) return all;
  ShadowCasters casters = all;
  casters.meshes.draws.clear();
  casters.strands.segment_count = 0;
  casters.volumes.volume_mask = 0;
  uint32_t first_segment = ~0u, end_segment = 0;
  for (uint32_t object : *map.objects) {
    const CasterObject& o = objects_.at(object);
    switch (o.kind) {
      case CasterObject::Kind::mesh_draw:
        if (o.first < all.meshes.draws.size()) casters.meshes.draws.push_back(all.meshes.draws[o.first]);
        break;
      case CasterObject::Kind::strands:
        first_segment = std::min(first_segment, o.first);
        end_segment = std::max(end_segment, o.first + o.count);
        break;
      case CasterObject::Kind::volume:
        if (o.first < kMaxClusteredVolumes) casters.volumes.volume_mask |= 1u << o.first;
        break;
    }
  }
  // A cluster's grooms are one range of segments (cluster_casters() keeps them contiguous).
  if (end_segment > first_segment && first_segment < all.strands.segment_count) {
    casters.strands.first_segment = first_segment;
    casters.strands.segment_count = std::min(end_segment, all.strands.segment_count) - first_segment;
  }
  if (casters.volumes.volume_mask == 0) casters.volumes.volume_count = 0;
  return casters;
}

FixedBuildStats ShadowMaps::fixed_build_stats(const MapState& map, uint32_t slot) const {
  uint32_t counters[4] = {0, 0, 0, 0};  // kFixedCounter* (shared/hair_bins.h)
  std::memcpy(counters, map.fixed_counter[slot].mapped(), sizeof(counters));
  const DeclaredMap& declared = map.declared[slot];
  const uint32_t resolution = declared.map_state.layout.resolution;
  FixedBuildStats f;
  f.inserted_segments = counters[shared::kFixedCounterInserted];
  const uint64_t entry_bytes = HairBinsPass::entry_bytes(declared.hair_segments, ctx_.info().max_storage_buffer_range);
  f.light_depth_bytes = LightDepthPass::bytes(resolution);
  f.hair_bin_capacity = declared.hair_segments == 0 ? 0 : entry_bytes / sizeof(uint32_t);
  f.hair_bin_bytes = HairBinsPass::tile_bytes(resolution) + entry_bytes;
  f.hair_bin_requested = counters[shared::kFixedCounterBinEntries];
  f.tiles_walked = counters[shared::kFixedCounterTilesWalked];
  return f;
}

// One map's figures of the frame completed in `slot`, read against what that frame
// declared; grows its capture (and the technique's state) for the next frame declared,
// from what later frames already have. Sets `remake` when the atlas or the list buffers
// must be made again.
LightShadowStats ShadowMaps::finish_map(MapState& map, uint32_t slot, bool& remake) {
  const LightState& light = lights_[map.light];
  const DeclaredMap& declared = map.declared[slot];
  LightShadowStats stats;
  uint32_t counters[3] = {0, 0, 0};  // capture segments, what the technique's build asked for
  if (declared.captured_lists) std::memcpy(counters, map.counter[slot].mapped(), sizeof(counters));
  const uint32_t requested = counters[0];
  const AvsmMapLayout& layout = declared.map_state.layout;
  stats.technique = light.light.shadow.technique;
  stats.nodes = layout.nodes;
  stats.resolution = layout.resolution;
  stats.mip_levels = layout.levels;
  stats.capture_capacity = declared.capacity;
  stats.capture_requested = requested;
  const uint64_t texels = uint64_t(layout.resolution) * layout.resolution;
  stats.capture_bytes = declared.captured_lists ? declared.capacity * kCaptureSegmentBytes + texels * 4 : 0;
  if (light.light.shadow.build == scene::ShadowBuild::fixed) stats.fixed_build = fixed_build_stats(map, slot);
  stats.overflowed = requested > declared.capacity;
  if (requested > map.capacity) {
    const uint64_t limit = options_.capture_limit_bytes / kCaptureSegmentBytes;
    const uint64_t grown = std::min(limit, round_up(requested + requested / 4, 1024));
    // The capture lists are transient, sized by each frame's graph; only the copies
    // that lookups read are buffers of this size.
    remake = remake || (grown > map.capacity && map.lookups_read_lists);
    map.capacity = std::max(map.capacity, grown);
  }
  stats.next_capture_capacity = map.capacity;
  stats.grew = stats.next_capture_capacity > stats.capture_capacity;
  // The technique's figures against the state the frame had; its next state from the current one.
  TechniqueMapState as_declared = declared.map_state;
  if (light.technique->finish_frame(counters, as_declared, stats)) stats.grew = true;  // a larger map next frame
  LightShadowStats against_current;
  if (light.technique->finish_frame(counters, map.map_state, against_current)) remake = true;
  return stats;
}

namespace {

// Figures of a light's several maps as one: sums, and whether any lost shadowing.
void add_map_stats(LightShadowStats& light, const LightShadowStats& map) {
  light.technique = map.technique;
  light.nodes = map.nodes;
  light.resolution = map.resolution;
  light.mip_levels = map.mip_levels;
  light.capture_capacity += map.capture_capacity;
  light.capture_requested += map.capture_requested;
  light.capture_bytes += map.capture_bytes;
  light.overflowed = light.overflowed || map.overflowed;
  light.next_capture_capacity += map.next_capture_capacity;
  light.grew = light.grew || map.grew;
  if (map.dsm_pool) {
    DsmPoolStats pool = light.dsm_pool.value_or(DsmPoolStats{});
    pool.requested_nodes += map.dsm_pool->requested_nodes;
    pool.capacity_nodes += map.dsm_pool->capacity_nodes;
    pool.overflowed = pool.overflowed || map.dsm_pool->overflowed;
    pool.build_dispatches = std::max(pool.build_dispatches, map.dsm_pool->build_dispatches);
    pool.needed_dispatches = std::max(pool.needed_dispatches, map.dsm_pool->needed_dispatches);
    pool.build_cut_short = pool.build_cut_short || map.dsm_pool->build_cut_short;
    light.dsm_pool = pool;
  }
  if (map.fixed_build) {
    FixedBuildStats f = light.fixed_build.value_or(FixedBuildStats{});
    f.inserted_segments += map.fixed_build->inserted_segments;
    f.light_depth_bytes = std::max(f.light_depth_bytes, map.fixed_build->light_depth_bytes);  // transient, aliased
    f.hair_bin_bytes = std::max(f.hair_bin_bytes, map.fixed_build->hair_bin_bytes);
    f.hair_bin_capacity = std::max(f.hair_bin_capacity, map.fixed_build->hair_bin_capacity);
    f.hair_bin_requested += map.fixed_build->hair_bin_requested;
    f.tiles_walked += map.fixed_build->tiles_walked;
    light.fixed_build = f;
  }
}

}  // namespace

void ShadowMaps::finish_frame(uint32_t slot) {
  if (slot >= frames_in_flight())
    throw std::invalid_argument("ShadowMaps::finish_frame: frame slot " + std::to_string(slot) + " of " +
                                std::to_string(frames_in_flight()) + " frames in flight");
  retired_.finished(slot);
  bool remake = false;
  std::vector<LightShadowStats> per_light(lights_.size());
  std::vector<TechniqueMapState> before;
  for (const MapState& map : maps_) before.push_back(map.map_state);
  for (MapState& map : maps_) {
    map.stats = finish_map(map, slot, remake);
    add_map_stats(per_light[map.light], map.stats);
  }
  // Maps that grew (deep shadow map pools) stay within the budget: past it they keep
  // their size, and the frames go on reporting what did not fit.
  if (atlas_bytes_needed() > map_budget())
    for (size_t m = 0; m < maps_.size(); ++m) maps_[m].map_state = before[m];
  if (remake) {
    // For the next frame. The frames still in flight bind the buffers replaced here (a
    // grown technique map, the looked-up lists: the uncompressed technique and the exact
    // reference): they keep them until they finish.
    for (gpu::Buffer* replaced : {&atlas_, &list_heads_, &list_nodes_}) retired_.retire(std::move(*replaced));
    create_list_buffers();
    create_atlas();
  }
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    LightShadowStats& stats = per_light[i];
    const LightState& light = lights_[i];
    stats.light = stats_[i].light;
    stats.maps = light.map_count;
    stats.map_kind = light.views == shared::kViewsCube        ? "cube"
                     : light.views == shared::kViewsCascades  ? "cascades"
                     : light.views == shared::kViewsClusters  ? "clusters"
                                                              : "single";
    stats.lowered_from = light.lowered_from;
    for (uint32_t m = light.first_map; m < light.first_map + light.map_count; ++m)
      stats.map_bytes += maps_[m].map ? maps_[m].map.size() : 0;  // after a pool growth: the new map
    stats_[i] = stats;
  }
}

}  // namespace avsm::passes
