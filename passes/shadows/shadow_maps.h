#pragma once
// Adaptive volumetric shadow maps for every light of a scene, as frame-graph
// passes (Salvi et al., EGSR 2010). A light has one map, or several: a point light
// six cube faces, a cascaded directional light one per split of the camera's view, a
// clustered light one per group of casters (seed 004). Per map and frame:
//   clear lists -> capture opaque -> capture hair -> capture smoke -> [sort lists]
//   -> the light's technique's build passes (passes/shadows/techniques/: avsm resolve and
//      mips, osm, fom or dsm builds), or none: the exact reference (uncompressed)
//      reads the capture lists themselves (copied for the lookups, "copy lists").
// The fixed-memory build replaces the lists with a build straight from the casters.
// All techniques share the capture. The lists are transient graph resources, so maps
// alias each other's capture memory. Every map is a region of one persistent atlas
// buffer, which the lookups address by each record's offset (shaders/shared/shadow.h),
// so any number of lights needs the same four bindings; its size is checked against
// a budget before anything is allocated.
//
// Capture overflow: the node buffer of each map holds a fixed number of
// segments. Segments beyond it are counted and dropped (never written out of
// bounds), so an overflowed frame has lighter shadows where the dropped segments
// were; frame_stats() reports it, and the next frame's buffer grows to fit (25%
// headroom) up to capture_limit_bytes.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <span>
#include <vector>

#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/techniques/avsm_map_layout.h"
#include "passes/shadows/capture/capture_hair_pass.h"
#include "passes/shadows/capture/capture_opaque_pass.h"
#include "passes/shadows/capture/capture_smoke_pass.h"
#include "passes/shadows/capture/capture_sort_pass.h"
#include "passes/frame/frames_in_flight.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/pages/page_table.h"
#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/shadow_clusters.h"
#include "passes/shadows/shadow_inputs.h"
#include "passes/shadows/shadow_settings.h"
#include "passes/shadows/techniques/technique.h"
#include "passes/shadows/shadow_stats.h"
#include "passes/frame/view.h"
#include "scene/scene.h"

namespace avsm::passes {

// Maps that do not fit the budget (ShadowOptions::map_budget_bytes): names the lights
// and their bytes, and the settings to change.
class ShadowBudgetError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class ShadowMaps {
 public:
  ShadowMaps(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Every scene light casts, with its ShadowSettings; each map is fitted as its
  // settings say (shadow.fit) around the scene's bounds. Throws std::invalid_argument for
  // settings this build cannot render (bad N, an unknown technique parameter value) and
  // ShadowBudgetError for maps over the budget, naming the scene.
  void set_scene(const scene::Scene& scene, const ShadowOptions& options = {});
  // The same for lights that come without a scene: each light's map is fitted around
  // `casters` (everything that casts or receives: what the map must cover; empty
  // bounds give a unit box at the origin). `objects` are what clustered maps group
  // (lights with shadow.clusters > 1 need them). Both wait for the device to idle
  // (frames in flight use the buffers they replace).
  void set_lights(const std::vector<scene::Light>& lights, const scene::Bounds& casters,
                  const ShadowOptions& options = {}, const std::vector<CasterObject>& objects = {});

  // How many frames may be in flight (passes/frame/frames_in_flight.h; 1 by default): the
  // parameter blocks and capture counters get a copy per frame slot. Waits for the
  // device to idle.
  void set_frames_in_flight(uint32_t count);
  uint32_t frames_in_flight() const { return parameters_.frames(); }
  // Moves light `light` (its position and direction; the rest of its settings stay) for
  // the next frame, without waiting for frames in flight: its maps are fitted again.
  // A clustered light keeps its clusters. Throws std::out_of_range for a light it lacks.
  void place_light(uint32_t light, const glm::vec3& position, const glm::vec3& direction);

  // Casters changed inside these world bounds: a moved caster's old and new bounds, or
  // the bounds of one that appeared, vanished or changed (a volume's density, a hair
  // edit). The pages of paged maps that they overlap are built again when next asked
  // for; every other page stays as it is. Dense maps are built every frame and need
  // nothing. Returns the pages invalidated. The change must not take effect in a frame
  // in flight (casters are read as static data: ShadowCasters).
  uint32_t casters_changed(std::span<const scene::Bounds> world_bounds);
  // Caster object `object` (of those set_scene()/set_lights() took) now lies in `bounds`:
  // the pages its old and new bounds overlap are built again, and page builds cull it by
  // its new bounds. Throws std::out_of_range for an object it lacks.
  uint32_t caster_moved(uint32_t object, const scene::Bounds& bounds);

  // Declares this frame's shadow passes for every light's maps into frame slot `slot`,
  // whose previous frame must have completed; their persistent resources (the map
  // atlas, capture counters) are imported with the graph (rg::vulkan::import).
  // Maps fitted to the view follow `camera`. `casters` are captured by value: their
  // buffers must stay alive and unchanged until the frame completes. Returns what the
  // camera passes need to read the maps.
  ShadowInputs add_to_graph(rg::Graph& graph, const View& camera, const ShadowCasters& casters, uint32_t slot = 0);

  // Inputs that leave every light unshadowed (for camera passes used without maps).
  ShadowInputs unshadowed_inputs() const { return unshadowed_.inputs(); }

  // After the frame recorded into `slot` completed (frames finish in the order they
  // were declared): reads its capture counters, reports overflow, grows the node
  // buffers for the next frame declared. When the map atlas or the list buffers must be
  // made again, the frames still in flight keep the old ones until they finish (no wait).
  void finish_frame(uint32_t slot = 0);
  const std::vector<LightShadowStats>& frame_stats() const { return stats_; }
  // Fits the maps that follow the camera (shadow.fit view, cascades) to `camera` now, as
  // add_to_graph() does each frame: for code that needs light_views() before a frame.
  void follow_camera(const View& camera) { update_views(camera); }
  // Each light's first map's view (its only one but for point, cascaded and clustered lights).
  const std::vector<LightView>& light_views() const { return views_; }
  // Map lookups a point's transmittance takes over every light (at least 1): one per light,
  // two across a cascade split, a cluster map each, an area light's virtual lights each.
  uint32_t lookups_per_point() const;
  // Every map of light `light`, as the last frame declared them.
  std::vector<LightView> map_views(uint32_t light) const;
  uint32_t map_count(uint32_t light) const { return lights_.at(light).map_count; }
  // Light `light`'s first map (layout: map_layout(light)); empty for uncompressed lights.
  const gpu::Buffer& avsm_map(uint32_t light) const { return maps_.at(lights_.at(light).first_map).map; }
  // Light `light`'s first map's capture lists as the last frame copied them for the lookups
  // (sorted if its settings sort): the heads row by row (kListEnd: empty) and the nodes they
  // and each segment's `next` index. Empty buffers unless lookups read the lists
  // (ShadowOptions::keep_reference, or the uncompressed technique).
  const gpu::Buffer& looked_up_list_heads(uint32_t light) const {
    return maps_.at(lights_.at(light).first_map).list_heads;
  }
  const gpu::Buffer& looked_up_list_nodes(uint32_t light) const {
    return maps_.at(lights_.at(light).first_map).list_nodes;
  }
  // The state every frame leaves the maps in (read by the camera passes' shaders): what a
  // later graph reading a map back imports it in.
  static rg::ImportState map_state_after_frame() { return rg::ImportState::of(rg::Usage::StorageRead); }
  const AvsmMapLayout& map_layout(uint32_t light) const {
    return maps_.at(lights_.at(light).first_map).map_state.layout;
  }
  const ShadowTechnique& technique(uint32_t light) const { return *lights_.at(light).technique; }
  uint32_t light_count() const { return uint32_t(lights_.size()); }
  // Light `light`'s maps are paged (shadow.layout "paged"): light_views() gives the
  // virtual map, map_layout() one page build's.
  bool is_paged(uint32_t light) const { return is_paged(lights_.at(light)); }
  // Its pages' figures as the last finished frame left them (summed over a point light's faces).
  const PageTable* page_table(uint32_t map) const { return maps_.at(map).pages.get(); }
  // Counts the frames declared that change light `light`'s maps: every frame for dense
  // maps (rebuilt each frame), only frames that build pages or change the page table for
  // paged ones. What reads a map may skip a frame whose revision it has already read.
  uint64_t map_revision(uint32_t light) const;
  bool has_reference() const { return options_.keep_reference; }
  // Light `light`'s lookups have an exact reference: the frame keeps references, and its
  // maps are dense or the frame keeps paged references too (keep_paged_reference).
  bool has_reference(uint32_t light) const {
    return options_.keep_reference && (options_.keep_paged_reference || !is_paged(lights_.at(light)));
  }
  // Where paged light `light`'s level-0 texel (x, y) of its first map is held, as the
  // CPU's table says (the frames declared since it may have moved pages): the finest
  // level with a resident page over it, and that level's texel's first vec4 in
  // avsm_map(light). Nullopt for dense lights and texels no level holds.
  struct PagedTexel {
    uint32_t level = 0;
    uint64_t map_vec4 = 0;
  };
  std::optional<PagedTexel> paged_texel(uint32_t light, uint32_t x, uint32_t y) const;
  // Bytes of the one buffer every map lives in.
  uint64_t atlas_bytes() const { return atlas_ ? atlas_.size() : 0; }

 private:
  struct LightState {
    scene::Light light;
    const ShadowTechnique* technique = nullptr;
    uint32_t views = shared::kViewsSingle;  // how the lookup picks among its maps
    uint32_t first_map = 0, map_count = 1;
    uint32_t lowered_from = 0;  // resolution before the budget lowered it; 0: not lowered
    std::vector<float> cascade_ends;  // the last frame's, cascaded lights only
    // Paged: the pages the frame being declared builds, every face's (its first map plans
    // them for all: they share one pool).
    std::vector<PageBuild> planned_page_builds;
  };
  // What a frame declared for a map, which its figures are read against when it
  // completes (later frames may already have grown the capture).
  struct DeclaredMap {
    uint64_t capacity = 0;
    TechniqueMapState map_state;
    bool captured_lists = false;
    uint32_t hair_segments = 0;  // sizes the fixed build's bins
    std::vector<PageBuild> page_builds;  // paged maps: the pages it built
    PageStats pages;                     // and the pool as it left it
    std::vector<uint32_t> page_table;    // the table its lookups read
    glm::uvec2 page_window_centre{0u};   // where the table's clipmap windows were
    // The regions its graph imported, which must outlive its execution (held by pointer:
    // the graph keeps their addresses).
    std::vector<std::unique_ptr<gpu::Buffer>> page_buffers;
  };
  // One map: a light's only one, a cube face, a cascade or a cluster's.
  struct MapState {
    uint32_t light = 0;
    uint32_t record = 0;  // its GpuShadow in the parameter buffer
    std::string prefix;   // its passes' names start with it ("light 0", "light 1 face 2")
    LightView view;
    int face = -1;               // a point light's cube face, else -1
    // An area light's one map: its virtual lights' maps, each a range of it
    // (make_virtual_light_maps); their records follow one another from first_virtual_record.
    std::vector<LightView> virtual_views;
    uint32_t first_virtual_record = 0;
    scene::Bounds fit_bounds;    // what it covers before a camera is known
    std::optional<std::vector<uint32_t>> objects;  // a cluster's CasterObjects; unset: every caster
    TechniqueMapState map_state;
    uint64_t atlas_offset = 0;
    gpu::Buffer map;            // a region of atlas_
    FrameBuffers counter;        // host-readable capture counter, per frame slot
    FrameBuffers fixed_counter;  // host-readable, the fixed build's (shared/hair_bins.h), per frame slot
    bool lookups_read_lists = false;
    uint64_t list_heads_offset = 0, list_nodes_offset = 0;  // bytes in list_heads_, list_nodes_
    gpu::Buffer list_heads, list_nodes;                     // regions of them
    std::vector<DeclaredMap> declared;  // per frame slot: its last frame's
    uint64_t capacity = 0;        // capture segments of the map (paged: of each page build)
    LightShadowStats stats;       // the last frame's
    // Paged maps (shadow.layout "paged"): the light's pages (its maps, a point light's
    // faces, share one table and pool), which face of it this map is, its page table (a
    // region of the atlas at atlas_offset), where the light's pool starts in the atlas
    // (after its first map's table), where its request bits start (in words), and per
    // frame slot the counters of its page builds.
    std::shared_ptr<PageTable> pages;
    uint32_t page_face = 0;
    gpu::Buffer page_table;
    uint64_t page_pool_offset = 0;
    uint32_t page_requests_offset = shared::kNoPageRequests;
    FrameBuffers page_counters;
    uint64_t revision = 0;  // dense: frames declared, each of which builds it (map_revision())
  };
  // Maps start on this many bytes in the atlas: above every device's storage buffer offset
  // alignment (the mips pass binds windows of a map at aligned offsets).
  static constexpr uint64_t kAtlasAlignment = 256;
  static constexpr uint64_t round_up(uint64_t value, uint64_t multiple) {
    return (value + multiple - 1) / multiple * multiple;
  }

  // shadow_maps.cpp: the lights and their maps.
  void add_light_maps(uint32_t light, const scene::Bounds& casters, const std::vector<CasterObject>& objects);
  void create_frame_buffers(MapState& map) const;
  // shadow_maps_atlas.cpp: the budget, the atlas, the looked-up lists.
  uint64_t map_budget() const;          // ShadowOptions::map_budget_bytes, at most the storage range
  TechniqueMapState initial_map_state(const LightState& light) const;
  uint64_t atlas_bytes(const MapState& map) const;  // aligned as the atlas places it
  uint64_t atlas_bytes_needed() const;  // every map, aligned as the atlas places them
  void fit_to_budget();
  void create_atlas();
  void create_list_buffers();
  std::string list_readers() const;
  // shadow_maps_views.cpp: the light views.
  void reset_view(MapState& map) const;
  LightView initial_view(const MapState& map) const;  // reset_view()'s for maps of one view
  void update_views(const View& camera);
  void move_page_windows(const View& camera);
  // shadow_maps_records.cpp: the frame's GpuShadow records.
  GpuShadow gpu_shadow(const MapState& map, const View& camera) const;
  GpuShadow virtual_light_record(const MapState& map, const GpuShadow& shared, uint32_t k) const;
  std::vector<GpuShadow> frame_records(const View& camera) const;
  rg::BufferHandle add_parameter_upload(rg::Graph& graph, const View& camera, uint32_t slot) const;
  // shadow_maps_graph.cpp: the frame's passes.
  CaptureLists add_capture_lists(rg::Graph& graph, const MapState& map, const ShadowCasters& casters,
                                 uint32_t slot) const;
  // Lists of `resolution`^2 texels holding each of `views` (one, or an area light's virtual lights).
  CaptureLists add_capture_lists(rg::Graph& graph, const std::string& prefix, uint32_t resolution,
                                 const std::vector<LightView>& views, bool sort, uint64_t capacity,
                                 rg::BufferHandle counter, const ShadowCasters& casters) const;
  void add_list_copy(rg::Graph& graph, const MapState& map, const CaptureLists& lists, ShadowInputs& inputs) const;
  void add_list_copy(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                     const gpu::Buffer& target_heads, const gpu::Buffer& target_nodes, uint32_t resolution,
                     uint64_t node_bytes, ShadowInputs& inputs) const;
  void add_page_list_copy(rg::Graph& graph, DeclaredMap& declared, const MapState& map, const PageBuild& page,
                          const std::string& prefix, const CaptureLists& lists, ShadowInputs& inputs) const;
  ShadowCasters casters_of(const MapState& map, const ShadowCasters& all) const;
  ShadowCasters select_casters(const ShadowCasters& all, const std::vector<uint32_t>& objects) const;
  // shadow_maps_pages.cpp: paged maps (shadow.layout "paged").
  static bool is_paged(const LightState& light) { return light.light.shadow.layout == scene::ShadowLayout::paged; }
  // The light's pool in pages, held in the atlas after its first map's table.
  void place_list_pool(MapState& map, uint64_t& heads, uint64_t& nodes);
  uint32_t pool_slots_in_atlas(const MapState& map) const { return map.page_face == 0 ? map.pages->slots() : 0u; }
  uint64_t page_table_bytes(const MapState& map) const;
  uint64_t page_counter_stride() const;
  uint64_t paged_atlas_bytes(const MapState& map) const;
  std::shared_ptr<PageTable> create_page_table(const LightState& light) const;
  void create_page_state(MapState& map, std::shared_ptr<PageTable> pages) const;
  void create_page_requests();
  rg::BufferHandle add_page_requests_clear(rg::Graph& graph, uint32_t slot) const;
  void add_page_builds(rg::Graph& graph, MapState& map, const ShadowCasters& casters, uint32_t slot,
                       ShadowInputs& inputs);
  void add_page_build(rg::Graph& graph, MapState& map, DeclaredMap& declared, uint32_t index,
                      const ShadowCasters& casters, uint32_t slot, ShadowInputs& inputs);
  void add_page_pool_imports(rg::Graph& graph, const MapState& map, DeclaredMap& declared, ShadowInputs& inputs) const;
  void add_page_table_upload(rg::Graph& graph, const MapState& map, const DeclaredMap& declared,
                             ShadowInputs& inputs) const;
  // The caster objects a page build takes (the map's, overlapping the page), given each
  // object's footprint on the map; all of the map's casters when there are no objects.
  ShadowCasters page_casters(const MapState& map, const ShadowCasters& all, const std::vector<UvRect>& footprints,
                             const PageKey& page) const;
  void finish_pages(MapState& map, uint32_t slot, LightShadowStats& stats);
  void finish_page_requests(MapState& map, uint32_t slot, LightShadowStats& stats);
  // shadow_maps_finish.cpp: a completed frame's figures.
  FixedBuildStats fixed_build_stats(const MapState& map, uint32_t slot) const;
  LightShadowStats finish_map(MapState& map, uint32_t slot, bool& remake);

  gpu::Context& ctx_;
  CaptureOpaquePass capture_opaque_;
  CaptureHairPass capture_hair_;
  CaptureSmokePass capture_smoke_;
  CaptureSortPass sort_;
  std::vector<std::unique_ptr<TechniqueBuilder>> builders_;  // by technique code - 1
  ShadowOptions options_;
  scene::Bounds casters_;
  std::vector<CasterObject> objects_;
  std::vector<LightView> views_;   // per light: its first map's
  std::vector<LightState> lights_;
  std::vector<MapState> maps_;
  uint32_t record_count_ = 0;      // GpuShadows per frame, before the exact references
  std::optional<View> last_camera_;  // the last frame's: new lights' maps fit to it until the next
  std::vector<LightShadowStats> stats_;
  gpu::Buffer atlas_;              // every map, at MapState::atlas_offset
  gpu::Buffer list_heads_, list_nodes_;  // copies of the lists lookups read
  FrameBuffers parameters_;  // GpuShadow per record (and per exact reference), written in the frame
  FrameBuffers page_requests_;  // the paged maps' request bits, per frame slot (read back)
  uint32_t page_request_words_ = 0;
  RetiredBuffers retired_;   // what finish_frame() replaced while frames in flight use it
  UnshadowedInputs unshadowed_;
};

}  // namespace avsm::passes
