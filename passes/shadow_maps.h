#pragma once
// Adaptive volumetric shadow maps for every light of a scene, as frame-graph
// passes (Salvi et al., EGSR 2010). Per light and frame:
//   clear lists -> capture opaque -> capture hair -> capture smoke -> [sort lists]
//   -> the light's technique's build passes (passes/techniques/: avsm resolve and
//      mips, osm, fom or dsm builds), or none: the exact reference (uncompressed)
//      reads the capture lists themselves.
// All techniques share the capture. The lists are transient graph resources, so
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
#include <memory>
#include <string>
#include <vector>

#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/avsm_map_layout.h"
#include "passes/capture_hair_pass.h"
#include "passes/capture_opaque_pass.h"
#include "passes/capture_smoke_pass.h"
#include "passes/capture_sort_pass.h"
#include "passes/light_view.h"
#include "passes/shadow_casters.h"
#include "passes/shadow_inputs.h"
#include "passes/techniques/technique.h"
#include "passes/shadow_stats.h"
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

  // Declares this frame's shadow passes for every light; their persistent resources
  // (maps, capture counters) are imported with the graph (rg::vulkan::import). `casters`
  // are captured by value: their buffers must stay alive and unchanged until the frame
  // completes. Returns what the camera passes need to read the maps.
  ShadowInputs add_to_graph(rg::Graph& graph, const View& camera, const ShadowCasters& casters);

  // Inputs that leave every light unshadowed (for camera passes used without maps).
  ShadowInputs unshadowed_inputs() const { return unshadowed_.inputs(); }

  // After the frame completed: reads the capture counters, reports overflow,
  // grows the node buffers for the next frame.
  void finish_frame();
  const std::vector<LightShadowStats>& frame_stats() const { return stats_; }
  const std::vector<LightView>& light_views() const { return views_; }
  // Light `light`'s AVSM map (layout: map_layout(light)); empty for uncompressed lights.
  const gpu::Buffer& avsm_map(uint32_t light) const { return lights_.at(light).map; }
  // The state every frame leaves the maps in (read by the camera passes' shaders): what a
  // later graph reading a map back imports it in.
  static rg::ImportState map_state_after_frame() { return rg::ImportState::of(rg::Usage::StorageRead); }
  const AvsmMapLayout& map_layout(uint32_t light) const { return lights_.at(light).map_state.layout; }
  const ShadowTechnique& technique(uint32_t light) const { return *lights_.at(light).technique; }
  uint32_t light_count() const { return uint32_t(views_.size()); }
  bool has_reference() const { return options_.keep_reference; }

 private:
  struct LightState {
    scene::ShadowSettings settings;
    const ShadowTechnique* technique = nullptr;
    TechniqueMapState map_state;
    gpu::Buffer map;      // the technique's map (AVSM nodes, all levels; opacity planes; ...)
    gpu::Buffer counter;  // host-readable capture counter
    gpu::Buffer fixed_counter;  // host-readable, the fixed build's (shared/hair_bins.h)
    bool captured_lists = false;  // in the last frame declared
    uint32_t hair_segments = 0;   // in the last frame declared (sizes the fixed build's bins)
    uint64_t capacity = 0;
  };
  void create_map(uint32_t light);
  GpuShadow gpu_shadow(uint32_t light, const View& camera) const;
  rg::BufferHandle add_parameter_upload(rg::Graph& graph, const View& camera) const;
  FixedBuildStats fixed_build_stats(const LightState& light) const;
  CaptureLists add_capture_lists(rg::Graph& graph, uint32_t light, const ShadowCasters& casters) const;

  gpu::Context& ctx_;
  CaptureOpaquePass capture_opaque_;
  CaptureHairPass capture_hair_;
  CaptureSmokePass capture_smoke_;
  CaptureSortPass sort_;
  std::vector<std::unique_ptr<TechniqueBuilder>> builders_;  // by technique code - 1
  ShadowOptions options_;
  std::vector<LightView> views_;
  std::vector<LightState> lights_;
  std::vector<LightShadowStats> stats_;
  gpu::Buffer parameters_;  // GpuShadow per light (and per exact reference), written in the frame
  UnshadowedInputs unshadowed_;
};

}  // namespace avsm::passes
