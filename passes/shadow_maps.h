#pragma once
// Adaptive volumetric shadow maps for every light of a scene, as frame-graph
// passes (Salvi et al., EGSR 2010). Per light and frame:
//   clear lists -> capture opaque -> capture hair -> capture smoke -> [sort lists]
//   -> avsm resolve -> avsm mips            (technique avsm)
//   -> osm build                            (opacity shadow maps, K planes)
//   -> fom build                            (Fourier opacity maps, K terms)
//   -> dsm clear -> dsm build               (deep shadow maps, error threshold)
// or the capture lists themselves, read exactly by the camera passes (technique
// uncompressed, the ground truth). All techniques share the capture. The lists are transient graph resources, so
// lights alias each other's capture memory; the map and the capture counter are
// persistent and imported.
//
// Capture overflow: the node buffer of each light holds a fixed number of
// segments. Segments beyond it are counted and dropped (never written out of
// bounds), so an overflowed frame has lighter shadows where the dropped segments
// were; frame_stats() reports it, and the next frame's buffer grows to fit (25%
// headroom) up to capture_limit_bytes.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/avsm_map_layout.h"
#include "passes/avsm_mips_pass.h"
#include "passes/avsm_resolve_pass.h"
#include "passes/capture_hair_pass.h"
#include "passes/capture_opaque_pass.h"
#include "passes/capture_smoke_pass.h"
#include "passes/capture_sort_pass.h"
#include "passes/light_view.h"
#include "passes/map_build_pass.h"
#include "passes/shadow_casters.h"
#include "passes/shadow_inputs.h"
#include "passes/view.h"
#include "scene/scene.h"

namespace avsm::passes {

// Stand-ins bound where a light has no map or lists, and the parameter block of
// all-unshadowed lights: camera passes rendered without shadow maps use these.
class UnshadowedInputs {
 public:
  static constexpr uint32_t kMaxLights = 64;
  explicit UnshadowedInputs(gpu::Context& ctx);
  ShadowInputs inputs() const;

 private:
  gpu::Buffer parameters_;  // kMaxLights zeroed GpuShadows (technique 0)
  gpu::Image heads_;        // 1x1 R32_UINT, one empty list, GENERAL layout
};

// Per-light figures of the last frame (after finish_frame()).
struct LightShadowStats {
  std::string light;
  scene::ShadowTechnique technique = scene::ShadowTechnique::avsm;
  uint32_t nodes = 0, resolution = 0, mip_levels = 0;
  uint64_t map_bytes = 0;               // persistent map (0 for uncompressed)
  uint64_t capture_capacity = 0;        // segments the node buffer held this frame
  uint64_t capture_requested = 0;       // segments the captures asked for
  uint64_t capture_bytes = 0;           // heads + node buffer this frame
  bool overflowed = false;              // requested > capacity: segments were dropped
  uint64_t next_capture_capacity = 0;   // after growth
  // Deep shadow maps: nodes the texels' compressed curves needed and the pool held;
  // texels that did not fit read as unshadowed this frame (the pool grows for the next).
  uint64_t pool_requested = 0, pool_capacity = 0;
  bool pool_overflowed = false;
  bool grew = false;                    // a buffer grows for the next frame: rendering again does better
};

struct ShadowOptions {
  bool exponential_interpolation = false;
  float normal_offset_texels = 2.0f;           // receivers move this many texels along their normal
  uint64_t capture_limit_bytes = 128ull << 20;  // node buffer growth limit (lavapipe's maxStorageBufferRange)
  uint32_t smoke_samples_per_segment = CaptureSmokePass::kDefaultSamplesPerSegment;
  // Keep every light's capture lists to the end of the frame, so passes can look up
  // the exact (uncompressed) transmittance next to the technique's: GpuShadow entries
  // light_count() .. 2 * light_count() - 1 are the lights' exact references
  // (reference_light_transmittance() in shaders/common/shadow_lookup.glsl). Costs the
  // lists' memory for the whole frame (no aliasing between lights).
  bool keep_reference = false;
};

class ShadowMaps {
 public:
  ShadowMaps(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Every scene light casts (at most kMaxShadowedLights; more is an error naming
  // the scene), with its ShadowSettings, each map fitted around the scene's bounds.
  // Throws std::invalid_argument for settings this build cannot render (bad N, an
  // unknown technique parameter value).
  void set_scene(const scene::Scene& scene, const ShadowOptions& options = {});
  // The same for lights that come without a scene: each light's map is fitted around
  // `casters` (everything that casts or receives: what the map must cover; empty
  // bounds give a unit box at the origin).
  void set_lights(const std::vector<scene::Light>& lights, const scene::Bounds& casters,
                  const ShadowOptions& options = {});

  // Declares this frame's shadow passes for every light and binds their persistent
  // resources to `executor`. `casters` are captured by value: their buffers must stay
  // alive and unchanged until the frame completes. Returns what the camera passes
  // need to read the maps.
  ShadowInputs add_to_graph(rg::Graph& graph, rg::vulkan::Executor& executor, const View& camera,
                            const ShadowCasters& casters);

  // Inputs that leave every light unshadowed (for camera passes used without maps).
  ShadowInputs unshadowed_inputs() const { return unshadowed_.inputs(); }

  // After the frame completed: reads the capture counters, reports overflow,
  // grows the node buffers for the next frame.
  void finish_frame();
  const std::vector<LightShadowStats>& frame_stats() const { return stats_; }
  const std::vector<LightView>& light_views() const { return views_; }
  const gpu::Buffer& parameters() const { return parameters_; }
  // Light `light`'s AVSM map (layout: map_layout(light)); empty for uncompressed lights.
  const gpu::Buffer& avsm_map(uint32_t light) const { return lights_.at(light).map; }
  // The state every frame leaves the maps in (read by the camera passes' shaders): what a
  // later graph reading a map back imports it in.
  static rg::ImportState map_state_after_frame() { return rg::ImportState::of(rg::Usage::StorageRead); }
  const AvsmMapLayout& map_layout(uint32_t light) const { return lights_.at(light).layout; }
  uint32_t light_count() const { return uint32_t(views_.size()); }
  bool has_reference() const { return options_.keep_reference; }

 private:
  struct LightState {
    scene::ShadowSettings settings;
    AvsmMapLayout layout;
    gpu::Buffer map;      // the technique's map (AVSM nodes, all levels; opacity planes; ...)
    gpu::Buffer counter;  // host-readable capture counter
    uint64_t capacity = 0;
    uint64_t pool_nodes = 0;  // deep shadow map node pool
  };
  void create_map(uint32_t light);
  GpuShadow gpu_shadow(uint32_t light, const View& camera) const;

  gpu::Context& ctx_;
  CaptureOpaquePass capture_opaque_;
  CaptureHairPass capture_hair_;
  CaptureSmokePass capture_smoke_;
  CaptureSortPass sort_;
  AvsmResolvePass resolve_;
  AvsmMipsPass mips_;
  MapBuildPass osm_build_, fom_build_, dsm_build_;
  ShadowOptions options_;
  std::vector<LightView> views_;
  std::vector<LightState> lights_;
  std::vector<LightShadowStats> stats_;
  gpu::Buffer parameters_;  // HostUpload, GpuShadow per light
  UnshadowedInputs unshadowed_;
};

}  // namespace avsm::passes
