// ShadowMaps' paged maps (shadow.layout "paged"; shaders/shared/pages.h): the pool's size
// and place in the atlas, the request bits the camera's receivers mark, the frame's page
// builds (each page captured and resolved like a small dense map over its window of the
// virtual map), the page table's upload, and what a completed frame asked for next.
#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "gpu/context.h"
#include "passes/shadows/shadow_maps.h"

namespace avsm::passes {

// A page build's capture counter (16 bytes: CaptureLists::counter), on the device's
// storage buffer offset alignment, since each is bound on its own.
uint64_t ShadowMaps::page_counter_stride() const {
  return round_up(16, std::max<uint64_t>(ctx_.info().min_storage_buffer_offset_alignment, 16));
}

uint64_t ShadowMaps::page_table_bytes(const MapState& map) const {
  const scene::Light& light = lights_[map.light].light;
  const uint32_t entries = shared::page_table_entries(uint32_t(light.shadow.virtual_resolution),
                                                      uint32_t(light.shadow.page_size), paged_window_pages(light));
  return round_up(uint64_t(entries) * 4, kAtlasAlignment);
}

// The table, then (the light's first map) the pool of AVSM pages; a pool of lists lives
// in the looked-up list buffers instead (create_list_buffers()).
uint64_t ShadowMaps::paged_atlas_bytes(const MapState& map) const {
  const scene::ShadowSettings& s = lights_[map.light].light.shadow;
  if (paged_keeps_lists(s)) return page_table_bytes(map);
  return page_table_bytes(map) + uint64_t(pool_slots_in_atlas(map)) * paged_slot_bytes(s);
}

// One table and pool for all of a light's maps: a point light's faces take the slots
// their receivers ask for, from one pool of shadow.page_pool_mib.
std::shared_ptr<PageTable> ShadowMaps::create_page_table(const LightState& light) const {
  const scene::ShadowSettings& s = light.light.shadow;
  const uint32_t window = paged_window_pages(light.light);
  auto pages = std::make_shared<PageTable>(uint32_t(s.virtual_resolution), uint32_t(s.page_size),
                                           paged_pool_slots(s, 1), paged_fallback_level(s, light.map_count, window),
                                           light.map_count, window);
  if (options_.required_page_level >= 0) pages->require_level(uint32_t(options_.required_page_level));
  return pages;
}

void ShadowMaps::create_page_state(MapState& map, std::shared_ptr<PageTable> pages) const {
  map.pages = std::move(pages);
  map.page_face = uint32_t(std::max(map.face, 0));
  map.page_counters.set_frames(ctx_, frames_in_flight());
  map.page_counters.create(ctx_, {map.pages->slots() * page_counter_stride(),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  gpu::MemoryLocation::HostReadback, map.prefix + " page capture counters"});
}

// One bit per page-table entry of every paged map, per frame slot.
void ShadowMaps::create_page_requests() {
  page_request_words_ = 0;
  for (MapState& map : maps_) {
    map.page_requests_offset = shared::kNoPageRequests;
    if (!map.pages) continue;
    map.page_requests_offset = page_request_words_;
    page_request_words_ += (map.pages->face_entries() + 31) / 32;
  }
  page_requests_ = {};
  if (page_request_words_ == 0) return;
  page_requests_.set_frames(ctx_, frames_in_flight());
  page_requests_.create(ctx_, {uint64_t(page_request_words_) * 4,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               gpu::MemoryLocation::HostReadback, "shadow page requests"});
}

// "clear page requests": the frame's receivers mark the bits from nothing.
rg::BufferHandle ShadowMaps::add_page_requests_clear(rg::Graph& graph, uint32_t slot) const {
  rg::BufferHandle requests = rg::vulkan::import(graph, "shadow page requests", page_requests_[slot],
                                                 rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  struct Data {
    rg::BufferHandle requests;
  };
  return graph.add_pass<Data>("clear page requests", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b, Data& d) { d.requests = b.write(requests, rg::Usage::TransferDst); },
      [](const Data& d, rg::PassContext& c) {
        const gpu::BufferRange target = c.buffer(d.requests);
        vkCmdFillBuffer(c.cmd(), target, target.offset, target.size, 0u);
      })
      .requests;
}

// The pages the page table picks for this frame, each captured over its window and
// resolved into its slot; then the page table, which the frame's lookups read.
void ShadowMaps::add_page_builds(rg::Graph& graph, MapState& map, const ShadowCasters& casters, uint32_t slot,
                                 ShadowInputs& inputs) {
  LightState& light = lights_[map.light];
  // The light's first map plans every face's builds at once: a page of one face may take
  // the slot of another's, whose table must not be declared before that.
  if (map.page_face == 0)
    light.planned_page_builds =
        map.pages->plan_builds(options_.unlimited_page_builds ? 0u : uint32_t(light.light.shadow.page_builds_per_frame));
  DeclaredMap& declared = map.declared[slot];
  declared = {map.capacity, map.map_state, true, casters.strands.segment_count};
  for (const PageBuild& build : light.planned_page_builds)
    if (build.key.face == map.page_face) declared.page_builds.push_back(build);
  declared.pages = map.pages->stats();
  declared.page_table = map.pages->face_table_words(map.page_face);
  declared.page_window_centre = map.pages->window_centre();
  std::vector<UvRect> footprints(objects_.size());  // of the map's objects (culled per page)
  if (!declared.page_builds.empty())
    for (uint32_t o = 0; o < objects_.size(); ++o) footprints[o] = light_footprint(map.view, objects_[o].bounds);
  for (uint32_t i = 0; i < declared.page_builds.size(); ++i)
    add_page_build(graph, map, declared, i, page_casters(map, casters, footprints, declared.page_builds[i].key), slot,
                   inputs);
  if (map.page_face == 0) add_page_pool_imports(graph, map, declared, inputs);
  add_page_table_upload(graph, map, declared, inputs);
}

// Build `index` of the frame: the page's capture over its window; its lists copied into
// its slot of the pool of lists (the uncompressed technique, or the exact reference);
// the technique's map resolved into its slot of the pool.
void ShadowMaps::add_page_build(rg::Graph& graph, MapState& map, DeclaredMap& declared, uint32_t index,
                                const ShadowCasters& casters, uint32_t slot, ShadowInputs& inputs) {
  const LightState& light = lights_[map.light];
  const scene::ShadowSettings& settings = light.light.shadow;
  const PageBuild& page = declared.page_builds[index];
  const std::string prefix = map.prefix + " page " + std::to_string(page.key.level) + "/" +
                             std::to_string(page.key.page.x) + "," + std::to_string(page.key.page.y);
  const LightView view = page_view(map.view, page.key.level, page.key.page, uint32_t(settings.page_size),
                                   ctx_.info().max_viewport_dimension);
  const gpu::Buffer& counter_region = *declared.page_buffers.emplace_back(std::make_unique<gpu::Buffer>(
      gpu::Buffer::region(map.page_counters[slot], index * page_counter_stride(), 16, prefix + " capture counter")));
  rg::BufferHandle counter = rg::vulkan::import(graph, prefix + " capture counter", counter_region,
                                                rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  CaptureLists lists = add_capture_lists(graph, prefix, view.resolution, {view}, settings.sort, map.capacity, counter, casters);
  if (map.lookups_read_lists) add_page_list_copy(graph, declared, map, page, prefix, lists, inputs);
  if (!light.technique->has_map()) return;  // the uncompressed technique: its lists are its pages
  const uint64_t bytes_per_slot = paged_slot_bytes(settings);
  const rg::ImportState after = map_state_after_frame();
  const gpu::Buffer& slot_region = *declared.page_buffers.emplace_back(std::make_unique<gpu::Buffer>(gpu::Buffer::region(
      atlas_, map.page_pool_offset + page.slot * bytes_per_slot, bytes_per_slot, prefix + " avsm")));
  rg::BufferHandle handle = rg::vulkan::import(graph, prefix + " avsm", slot_region, rewritten_after(after), after);
  const TechniqueBuilder& builder = *builders_[light.technique->code() - 1];
  inputs.maps.push_back(builder.add_to_graph({graph, prefix, lists, handle, view, settings, map.map_state}, lists));
}

// The light's whole pools (imported once, with its first map), as the lookups read them:
// kept pages too, built in earlier frames. The pages built this frame are regions of
// them, which the graph orders before the lookups by their own handles; these imports
// carry the rest from frame to frame.
void ShadowMaps::add_page_pool_imports(rg::Graph& graph, const MapState& map, DeclaredMap& declared,
                                       ShadowInputs& inputs) const {
  const LightState& light = lights_[map.light];
  const std::string name = "light " + std::to_string(map.light) + " page pool";
  if (map.lookups_read_lists) {
    const rg::ImportState read = rg::ImportState::of(rg::Usage::StorageRead);
    inputs.lists.push_back(rg::vulkan::import(graph, name + " lists' heads", map.list_heads, read, read));
    inputs.lists.push_back(rg::vulkan::import(graph, name + " lists' nodes", map.list_nodes, read, read));
  }
  if (!light.technique->has_map()) return;
  const rg::ImportState after = map_state_after_frame();
  const uint64_t bytes = map.pages->slots() * paged_slot_bytes(light.light.shadow);
  const gpu::Buffer& pool = *declared.page_buffers.emplace_back(
      std::make_unique<gpu::Buffer>(gpu::Buffer::region(atlas_, map.page_pool_offset, bytes, name)));
  inputs.maps.push_back(rg::vulkan::import(graph, name, pool, after, after));
}

// The page table, as plan_builds() left it: pages built this frame are already in it.
void ShadowMaps::add_page_table_upload(rg::Graph& graph, const MapState& map, const DeclaredMap& declared,
                                       ShadowInputs& inputs) const {
  const rg::ImportState after = map_state_after_frame();
  rg::BufferHandle table = rg::vulkan::import(graph, map.prefix + " page table", map.page_table, rewritten_after(after), after);
  struct Data {
    rg::BufferHandle table;
  };
  inputs.maps.push_back(graph.add_pass<Data>(map.prefix + " page table", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b, Data& d) { d.table = b.write(table, rg::Usage::TransferDst); },
      [words = declared.page_table](const Data& d, rg::PassContext& c) {
        constexpr size_t kPerCall = (64 << 10) / sizeof(uint32_t);  // vkCmdUpdateBuffer's limit
        const gpu::BufferRange target = c.buffer(d.table);
        for (size_t first = 0; first < words.size(); first += kPerCall) {
          const size_t count = std::min(kPerCall, words.size() - first);
          vkCmdUpdateBuffer(c.cmd(), target, target.offset + first * 4, count * 4, words.data() + first);
        }
      })
      .table);
}

// A page of lists: its capture's heads and nodes copied into its slot of the light's
// pool of lists (regions of the looked-up list buffers), where lookups walk them from
// then on.
void ShadowMaps::add_page_list_copy(rg::Graph& graph, DeclaredMap& declared, const MapState& map, const PageBuild& page,
                                    const std::string& prefix, const CaptureLists& lists, ShadowInputs& inputs) const {
  const uint64_t texels = uint64_t(map.map_state.layout.resolution) * map.map_state.layout.resolution;
  const uint64_t head_bytes = texels * sizeof(uint32_t), node_bytes = map.capacity * kCaptureSegmentBytes;
  const gpu::Buffer& heads = *declared.page_buffers.emplace_back(std::make_unique<gpu::Buffer>(gpu::Buffer::region(
      list_heads_, map.list_heads_offset + page.slot * head_bytes, head_bytes, prefix + " looked-up list heads")));
  const gpu::Buffer& nodes = *declared.page_buffers.emplace_back(std::make_unique<gpu::Buffer>(gpu::Buffer::region(
      list_nodes_, map.list_nodes_offset + page.slot * node_bytes, node_bytes, prefix + " looked-up list nodes")));
  add_list_copy(graph, prefix, lists, heads, nodes, map.map_state.layout.resolution, node_bytes, inputs);
}

ShadowCasters ShadowMaps::page_casters(const MapState& map, const ShadowCasters& all,
                                       const std::vector<UvRect>& footprints, const PageKey& page) const {
  if (objects_.empty()) return casters_of(map, all);  // nothing to cull by (a host's casters)
  // Widened by a texel of the page's level, as hair ribbons are (as invalidation does).
  const UvRect window = map.pages->window(page, 1.0f);
  std::vector<uint32_t> overlapping;
  auto take = [&](uint32_t object) {
    if (footprints[object].overlaps(window)) overlapping.push_back(object);
  };
  if (map.objects) {
    for (uint32_t object : *map.objects) take(object);
  } else {
    for (uint32_t object = 0; object < objects_.size(); ++object) take(object);
  }
  return select_casters(all, overlapping);
}

std::optional<ShadowMaps::PagedTexel> ShadowMaps::paged_texel(uint32_t light, uint32_t x, uint32_t y) const {
  const MapState& map = maps_[lights_.at(light).first_map];
  if (!map.pages) return std::nullopt;
  const PageTable& pages = *map.pages;
  const uint32_t size = pages.page_size(), nodes = uint32_t(lights_[light].light.shadow.nodes);
  if (x >= pages.virtual_resolution() || y >= pages.virtual_resolution()) return std::nullopt;
  for (uint32_t level = 0; level < pages.levels(); ++level) {
    const glm::uvec2 texel = glm::uvec2(x, y) >> level;
    const PageKey key{level, texel / size, map.page_face};
    if (!pages.has_entry(key)) continue;  // outside a clipmap level's window
    const uint32_t word = pages.table_words()[pages.entry(key)];
    if (word == shared::kPageAbsent) continue;
    const glm::uvec2 in_page = texel % size;
    const uint64_t slot_vec4 = (map.page_pool_offset - map.atlas_offset) / sizeof(glm::vec4) +
                               uint64_t(word - 1) * shared::page_slot_vec4s(size, nodes);
    return PagedTexel{level, slot_vec4 + (uint64_t(in_page.y) * size + in_page.x) * (nodes / 4)};
  }
  return std::nullopt;
}

uint64_t ShadowMaps::map_revision(uint32_t light) const {
  const LightState& state = lights_.at(light);
  uint64_t revision = 0;
  for (uint32_t m = state.first_map; m < state.first_map + state.map_count; ++m)
    revision += maps_[m].pages ? maps_[m].pages->revision() : maps_[m].revision;
  return revision;
}

uint32_t ShadowMaps::casters_changed(std::span<const scene::Bounds> world_bounds) {
  uint32_t invalidated = 0;
  for (MapState& map : maps_) {
    if (!map.pages) continue;
    std::vector<UvRect> footprints;
    for (const scene::Bounds& bounds : world_bounds) footprints.push_back(light_footprint(map.view, bounds));
    invalidated += map.pages->invalidate_overlapping(footprints, map.page_face);
  }
  return invalidated;
}

uint32_t ShadowMaps::caster_moved(uint32_t object, const scene::Bounds& bounds) {
  CasterObject& moved = objects_.at(object);
  const scene::Bounds both[2] = {moved.bounds, bounds};
  moved.bounds = bounds;
  return casters_changed(both);
}

// After the frame in `slot` completed: its page builds' capture figures (an overflowed
// page is built again with more room), and its receivers' requests for the next frame.
void ShadowMaps::finish_pages(MapState& map, uint32_t slot, LightShadowStats& stats) {
  const DeclaredMap& declared = map.declared[slot];
  const bool lists = map.lookups_read_lists;
  uint64_t most = 0;
  bool overflowed = false;
  for (size_t i = 0; i < declared.page_builds.size(); ++i) {
    uint32_t counter = 0;
    std::memcpy(&counter, static_cast<const char*>(map.page_counters[slot].mapped()) + i * page_counter_stride(), 4);
    most = std::max<uint64_t>(most, counter);
    if (counter <= declared.capacity) continue;
    overflowed = true;
    // Rebuilt when asked for again, with more room unless the lists cannot grow any more
    // (then reported); a page of lists holds what its slot holds, and is reported until
    // page_segments is raised.
    if (lists || declared.capacity < options_.capture_limit_bytes / kCaptureSegmentBytes)
      map.pages->invalidate(declared.page_builds[i].entry);
  }
  if (most > map.capacity && !lists) {
    const uint64_t limit = options_.capture_limit_bytes / kCaptureSegmentBytes;
    map.capacity = std::max(map.capacity, std::min(limit, round_up(most + most / 4, 1024)));
  }
  if (map.page_face == 0) finish_page_requests(map, slot, stats);  // every face's: the light's table
  const uint64_t texels = uint64_t(declared.map_state.layout.resolution) * declared.map_state.layout.resolution;
  stats.capture_capacity = declared.capacity;
  stats.capture_requested = most;  // of the largest page build, against one page build's capacity
  stats.capture_bytes = declared.page_builds.empty() ? 0 : declared.capacity * kCaptureSegmentBytes + texels * 4;
  stats.overflowed = overflowed;
  stats.next_capture_capacity = map.capacity;
  // Rendering again does better while requested pages wait (the budget, a growing bias).
  stats.grew = (overflowed && !lists) || (map.page_face == 0 && map.pages->has_pending_requests());
  stats.page_slot_full = overflowed && lists;
}

// The light's page figures, from its first map, and every face's requests of the frame
// completed in `slot` into the light's table.
void ShadowMaps::finish_page_requests(MapState& map, uint32_t slot, LightShadowStats& stats) {
  stats.pages = map.declared[slot].pages;
  stats.pages->pending = 0;
  if (!page_requests_) return;
  const LightState& light = lights_[map.light];
  const uint32_t entries = map.pages->face_entries(), words = (entries + 31) / 32;
  std::vector<std::span<const uint32_t>> faces;
  for (uint32_t m = light.first_map; m < light.first_map + light.map_count; ++m) {
    const MapState& face = maps_[m];
    const auto* bits = static_cast<const uint32_t*>(page_requests_[slot].mapped()) + face.page_requests_offset;
    // What the frame's receivers asked for and did not find (its table, not today's).
    const std::vector<uint32_t>& table = face.declared[slot].page_table;
    faces.emplace_back(bits, words);
    for_each_set_bit(faces.back(), entries, [&](uint32_t e) { stats.pages->pending += table[e] == shared::kPageAbsent; });
  }
  map.pages->add_requests(faces, map.declared[slot].page_window_centre);
  stats.pages->settling = map.pages->stats().settling;  // its requests moved the bias
}

}  // namespace avsm::passes
