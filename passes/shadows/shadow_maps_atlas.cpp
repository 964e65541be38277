// ShadowMaps' memory: the maps' bytes against the budget, the one atlas buffer every map
// is a region of, and the buffers of the capture lists that lookups read.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "gpu/context.h"
#include "gpu/device_limits.h"
#include "passes/shadows/shadow_maps.h"

namespace avsm::passes {

using gpu::format_mib;

namespace {

constexpr size_t kLightsNamed = 5;

// The kLightsNamed largest of `lights` (each its size and how a message names it), largest
// first, then how many more there are and, with `format_size`, their total: a message
// about 200 lights stays a readable line.
std::string largest_lights(std::vector<std::pair<uint64_t, std::string>> lights,
                           std::string (*format_size)(uint64_t) = nullptr) {
  std::stable_sort(lights.begin(), lights.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string text;
  uint64_t rest = 0;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (i < kLightsNamed)
      text += (i ? ", " : "") + lights[i].second;
    else
      rest += lights[i].first;
  }
  if (lights.size() > kLightsNamed) {
    const size_t more = lights.size() - kLightsNamed;
    text += " and " + std::to_string(more) + " more light" + (more > 1 ? "s" : "");
    if (format_size) text += " (" + format_size(rest) + ")";
  }
  return text;
}

}  // namespace

uint64_t ShadowMaps::map_budget() const {
  const uint64_t range = ctx_.info().max_storage_buffer_range;
  return options_.map_budget_bytes == 0 ? range : std::min(options_.map_budget_bytes, range);
}

// A map's state before its first frame, at its light's (possibly lowered) resolution.
TechniqueMapState ShadowMaps::initial_map_state(const LightState& light) const {
  // A paged map's builds are dense maps of a page each, of one level.
  // An area light's map holds its virtual lights' maps as ranges of its texels, none with mips.
  const bool paged = is_paged(light), virtual_lights = light.views == shared::kViewsVirtualLights;
  uint32_t resolution = uint32_t(paged ? light.light.shadow.page_size : light.light.shadow.resolution);
  if (virtual_lights)
    resolution = virtual_light_shared_resolution(resolution, uint32_t(light.light.virtual_lights));
  TechniqueMapState state;
  state.layout.resolution = resolution;
  state.layout.nodes = uint32_t(light.light.shadow.nodes);
  // Techniques without mips look trilinear up as bilinear.
  state.layout.levels = paged || virtual_lights ? 1 : light.technique->mip_levels(light.light.shadow, resolution);
  light.technique->prepare(state);
  return state;
}

// What a map takes of the atlas: its bytes, aligned as the atlas places it (0: no map).
uint64_t ShadowMaps::atlas_bytes(const MapState& map) const {
  const LightState& light = lights_[map.light];
  if (is_paged(light)) return round_up(paged_atlas_bytes(map), kAtlasAlignment);  // a table at least
  if (!light.technique->has_map()) return 0;
  return round_up(light.technique->map_bytes(light.light.shadow, map.map_state), kAtlasAlignment);
}

uint64_t ShadowMaps::atlas_bytes_needed() const {
  uint64_t bytes = 0;
  for (const MapState& map : maps_) bytes += atlas_bytes(map);
  return bytes;
}

// The maps' bytes against the budget: an error naming the lights, or (fit_budget) the
// largest lights' resolutions halved until everything fits.
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
      std::vector<std::pair<uint64_t, std::string>> named;
      for (size_t i = 0; i < lights_.size(); ++i) {
        const uint64_t bytes = light_bytes(lights_[i]);
        named.emplace_back(bytes, light_display_name(lights_[i].light, i) + " " + format_mib(bytes));
      }
      const std::string lights = largest_lights(std::move(named), format_mib);
      throw ShadowBudgetError("the shadow maps need " + format_mib(total()) + ", over the budget of " +
                              format_mib(budget) + (budget == range ? " (the device's storage buffer range)" : "") + ": " + lights +
                              "; lower their shadow.resolution, page_pool_mib or nodes, raise the budget (shadows.budget_mib) "
                              "or let it lower resolutions (shadows.fit_budget)");
    }
    // Halve the resolution of the light with the most bytes that can still go lower.
    LightState* largest = nullptr;
    for (LightState& light : lights_)
      if (!is_paged(light) && light.light.shadow.resolution > 16 && light_bytes(light) > 0 &&
          (!largest || light_bytes(light) > light_bytes(*largest)))
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
      reset_view(map);
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
    if (map.pages) {  // the page table, then (the light's first map) the light's pool
      const uint64_t table = page_table_bytes(map);
      map.map = gpu::Buffer::region(atlas_, map.atlas_offset, paged_atlas_bytes(map), map.prefix + " paged avsm map");
      map.page_table = gpu::Buffer::region(atlas_, map.atlas_offset, table, map.prefix + " page table");
      map.page_pool_offset = map.page_face == 0 ? map.atlas_offset + table : maps_[light.first_map].page_pool_offset;
      continue;
    }
    map.map = gpu::Buffer::region(atlas_, map.atlas_offset, light.technique->map_bytes(light.light.shadow, map.map_state),
                                  map.prefix + " " + light.light.shadow.technique + " map");
  }
}

// What sizes the looked-up lists, for a message when they do not fit: the resolution of
// every light whose lookups read its lists.
std::string ShadowMaps::list_readers() const {
  std::vector<std::pair<uint64_t, std::string>> named;
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    const MapState& first = maps_[lights_[i].first_map];
    if (!first.lookups_read_lists) continue;
    if (first.pages) {  // a pool of pages of lists
      const scene::ShadowSettings& s = lights_[i].light.shadow;
      named.emplace_back(uint64_t(first.pages->slots()) * s.page_size * s.page_size,
                         light_display_name(lights_[i].light, i) + " paged: " + std::to_string(first.pages->slots()) +
                             " slots of " + std::to_string(s.page_size) + "x" + std::to_string(s.page_size) + " texels, " +
                             std::to_string(paged_list_segments_per_texel(s)) + " segments a texel");
      continue;
    }
    const uint64_t side = first.map_state.layout.resolution;
    named.emplace_back(side * side * lights_[i].map_count,
                       light_display_name(lights_[i].light, i) + " " + std::to_string(side) + "x" + std::to_string(side) +
                           (lights_[i].map_count > 1 ? " x" + std::to_string(lights_[i].map_count) + " maps" : ""));
  }
  return "the shadow.resolution (--shadow-res) of the lights whose lookups read the exact lists (technique "
         "uncompressed, --compare-to), or for paged lights their page pool (--page-pool-mib) or page_segments "
         "(--shadow-param page_segments=N): " + largest_lights(std::move(named));
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
    if (map.pages && map.lookups_read_lists) {  // a pool of pages of lists, one per light
      place_list_pool(map, heads, nodes);
      continue;
    }
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
    // A paged map's regions: its light's whole pool (each page build copies into its slot).
    const uint64_t slots = map.pages ? map.pages->slots() : 1;
    map.list_heads = gpu::Buffer::region(list_heads_, map.list_heads_offset, slots * texels * sizeof(uint32_t),
                                         map.prefix + " looked-up list heads");
    map.list_nodes = gpu::Buffer::region(list_nodes_, map.list_nodes_offset, slots * map.capacity * kCaptureSegmentBytes,
                                         map.prefix + " looked-up list nodes");
  }
}

// A paged light's pool of lists (shadow.technique "uncompressed", or a paged light's exact
// reference): per slot, a page's heads and paged_list_slot_segments() segments, placed
// with the light's first map and shared by its faces. Its page captures hold no more
// than a slot.
void ShadowMaps::place_list_pool(MapState& map, uint64_t& heads, uint64_t& nodes) {
  const scene::ShadowSettings& s = lights_[map.light].light.shadow;
  map.capacity = paged_list_slot_segments(s);
  if (map.page_face != 0) {
    const MapState& first = maps_[lights_[map.light].first_map];
    map.list_heads_offset = first.list_heads_offset;
    map.list_nodes_offset = first.list_nodes_offset;
    return;
  }
  const uint64_t slots = map.pages->slots(), texels = uint64_t(s.page_size) * uint64_t(s.page_size);
  map.list_heads_offset = heads;
  map.list_nodes_offset = nodes;
  heads += round_up(slots * texels * sizeof(uint32_t), kAtlasAlignment);
  nodes += round_up(slots * map.capacity * kCaptureSegmentBytes, kAtlasAlignment);
}

}  // namespace avsm::passes
