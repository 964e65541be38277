// ShadowMaps' per-frame records: one GpuShadow per map and multi-map light (and per exact
// reference), what the lookups read (shaders/shared/shadow.h), written by the frame itself.
#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cmath>

#include "passes/shadows/shadow_maps.h"
#include "passes/shadows/techniques/techniques.h"

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

}  // namespace

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
  g.reference = has_reference(map.light) ? record_count_ + map.record : kNoReference;
  light.technique->fill(g, settings, v);
  if (map.pages) {  // the virtual map (shared/pages.h)
    g.resolution = map.pages->virtual_resolution();
    g.mip_count = map.pages->levels();
    g.filter_mode = shared::kFilterTrilinear;
    g.page_size = map.pages->page_size();
    g.page_pool_offset = uint32_t(map.page_pool_offset / sizeof(glm::vec4));
    g.page_requests_offset = map.page_requests_offset;
    g.page_lod_bias = settings.page_lod_bias + map.pages->lod_bias();
    g.page_volume_lod_bias = settings.page_volume_lod_bias;
    g.page_fallback_level = map.pages->fallback_level();
    g.page_window = map.pages->window_pages();
    g.page_window_centre = map.pages->window_centre();
    if (map.lookups_read_lists) g.page_slot_nodes = uint32_t(map.capacity);  // its pool's slots of lists
  } else {
    g.page_requests_offset = shared::kNoPageRequests;
  }
  return g;
}

// Virtual light k's record of an area light's map whose record is `shared`: its range of
// the map's texels and lists, seen from its own view, bilinear (the mean over the virtual
// lights is the soft shadow's filter, and the map has no mips).
GpuShadow ShadowMaps::virtual_light_record(const MapState& map, const GpuShadow& shared, uint32_t k) const {
  const LightView& v = map.virtual_views[k];
  const LightState& light = lights_[map.light];
  GpuShadow g = shared;
  g.light_from_world = v.light_from_world;
  g.depth_plane = v.depth_plane;
  g.texel_camera = glm::vec4(v.texel_size_base, v.texel_size_per_depth, v.far_depth, shared.texel_camera.w);
  g.resolution = v.resolution;
  g.mip_count = 1;
  g.filter_mode = std::min(g.filter_mode, shared::kFilterBilinear);
  g.kernel = shared::kKernelNone;
  const uint64_t texels = uint64_t(map.view.resolution) * map.view.resolution;
  const uint64_t texel_bytes = light.technique->map_bytes(light.light.shadow, map.map_state) / texels;
  g.map_offset += uint32_t(v.shared_first_texel * texel_bytes / sizeof(glm::vec4));
  g.list_heads_offset += v.shared_first_texel;
  g.reference = shared.reference == kNoReference ? kNoReference : record_count_ + map.first_virtual_record + k;
  return g;
}

// Every record of the frame: each map's, each multi-map light's (its first map's with how
// to find the others), then the exact references.
std::vector<GpuShadow> ShadowMaps::frame_records(const View& camera) const {
  std::vector<GpuShadow> records(uint64_t(record_count_) * (options_.keep_reference ? 2 : 1));
  for (const MapState& map : maps_) {
    records[map.record] = gpu_shadow(map, camera);
    for (uint32_t k = 0; k < map.virtual_views.size(); ++k)
      records[map.first_virtual_record + k] = virtual_light_record(map, records[map.record], k);
  }
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    const LightState& light = lights_[i];
    if (light.views == shared::kViewsSingle) continue;
    const MapState& first = maps_[light.first_map];
    GpuShadow& g = records[i];
    g = records[first.record];
    g.views = light.views;
    g.first_view = light.views == shared::kViewsVirtualLights ? first.first_virtual_record : first.record;
    g.view_count = light.views == shared::kViewsVirtualLights ? uint32_t(first.virtual_views.size()) : light.map_count;
    g.reference = has_reference(i) ? record_count_ + i : kNoReference;
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
      // A dense map's lists have no mips: the exact curve at every level of detail. A paged
      // map's pages of lists are its levels (the reference of the page a lookup reads).
      if (reference.page_size == shared::kDenseLayout) reference.mip_count = 1;
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

}  // namespace avsm::passes
