#pragma once
// A shadow technique: what turns a light's capture lists into something the camera
// passes look transmittance up in. Each lives in its own folder under
// passes/shadows/techniques/ (a module .cpp and the GLSL lookup <name>.glsl) and has one line
// in registry.h; ShadowMaps, the scene checks, the tools' help, the viewer panel and
// the reports go through the registry and never name a technique.
//
// The lookup GLSL defines
//   float <name>_texel_transmittance(GpuShadow s, uint level, ivec2 texel, float d)
// and, optionally (announced by #define AVSM_<NAME>_FIRST_OPAQUE_DEPTH),
//   float <name>_first_opaque_depth(GpuShadow s, ivec2 texel)
// for the light's debug image. The build generates the dispatch over the registry
// (techniques_dispatch.glsl), so shaders never switch on techniques by hand.
#include <rendergraph/graph.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "passes/shadows/techniques/avsm_map_layout.h"
#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/shadow_stats.h"
#include "scene/light.h"
#include "shared/shadow.h"

namespace avsm::gpu {
class Context;
class ShaderLibrary;
}  // namespace avsm::gpu

namespace avsm::passes {

// A number a technique reads from ShadowSettings::parameters, with its default and
// the values it accepts: min..max, a whole multiple of `multiple_of` when that is > 0.
struct TechniqueParameter {
  std::string_view name;
  double default_value = 0.0;
  double min = 0.0, max = 0.0;
  double multiple_of = 0.0;
  std::string_view meaning;  // for help texts
};

// A light's persistent map state as ShadowMaps keeps it; techniques size their map
// from it and may grow it between frames.
struct TechniqueMapState {
  AvsmMapLayout layout;     // resolution, AVSM nodes and mip levels
  uint64_t pool_nodes = 0;  // a variable-size node pool (deep shadow maps)
  uint32_t build_dispatches = 0;  // deep shadow maps: the build's dispatches after its first
};

// What a technique's build passes work with, for one light and frame.
struct TechniqueBuild {
  rg::Graph& graph;
  const std::string& prefix;  // "light <i>", the light's pass names start with it
  const CaptureLists& lists;  // read; `counter` may be updated (see MapBuilder::add_to_graph)
  rg::BufferHandle map;       // the imported persistent map
  const LightView& view;
  const scene::ShadowSettings& settings;
  const TechniqueMapState& state;
};

// What a technique's fixed-memory build works with (scene::ShadowBuild::fixed): the
// casters themselves instead of capture lists.
struct FixedTechniqueBuild {
  rg::Graph& graph;
  const std::string& prefix;
  rg::BufferHandle map;      // the imported persistent map
  rg::BufferHandle counter;  // 16 bytes, host readable (kFixedCounter* words of shared/hair_bins.h)
  const LightView& view;
  const scene::ShadowSettings& settings;
  const TechniqueMapState& state;
  const ShadowCasters& casters;
  uint32_t smoke_samples_per_segment;
};

// The GPU side of a technique on one device: its pipelines and how it adds its passes.
class TechniqueBuilder {
 public:
  virtual ~TechniqueBuilder() = default;
  // Declares the passes that fill `build.map`; returns the map's final version. May
  // replace `counter` in `lists` with its new version (a build that reports demand).
  virtual rg::BufferHandle add_to_graph(const TechniqueBuild& build, CaptureLists& lists) const = 0;
  // The fixed-memory build, for techniques whose builds_fixed(); returns the map's final version.
  virtual rg::BufferHandle add_fixed_to_graph(const FixedTechniqueBuild& build) const;
};

class ShadowTechnique {
 public:
  virtual ~ShadowTechnique() = default;

  virtual std::string_view name() const = 0;     // as scene files and command lines spell it
  virtual std::string_view summary() const = 0;  // one line for help texts
  // Extra settings it reads (besides resolution, filter and sort).
  virtual std::span<const TechniqueParameter> parameters() const { return {}; }
  // Throws std::invalid_argument naming `who` and the setting to change. The parameters
  // are checked against parameters() before this is called.
  virtual void check(const scene::ShadowSettings& settings, const std::string& who) const;
  // A short name with its size, as plots and reports print it ("AVSM-8").
  virtual std::string label(const scene::ShadowSettings& settings) const = 0;

  // Whether it keeps a persistent map (the exact reference reads the capture lists).
  virtual bool has_map() const { return true; }
  // Whether the camera passes read the light's capture lists at lookup time.
  virtual bool reads_capture_lists() const { return false; }
  // Whether it can build its map straight from the casters (scene::ShadowBuild::fixed).
  virtual bool builds_fixed() const { return false; }
  // Whether its map is its texels one after another, the same bytes each and nothing
  // else (map_bytes() / resolution^2 each, without mips), so that one map can hold
  // several views' maps as ranges of its texels (an area light's virtual lights').
  virtual bool map_is_texel_ranges() const { return true; }
  // Whether its map stores AVSM node curves (texel plots show the nodes).
  virtual bool stores_avsm_nodes() const { return false; }
  // Map mip levels for these settings (1: none).
  virtual uint32_t mip_levels(const scene::ShadowSettings&, uint32_t /*resolution*/) const { return 1; }
  // Sets up a light's map state before its first frame (`layout` is filled in).
  virtual void prepare(TechniqueMapState& /*state*/) const {}
  virtual uint64_t map_bytes(const scene::ShadowSettings& settings, const TechniqueMapState& state) const;

  // Its part of the light's GpuShadow record: node_count (what the lookup calls the
  // technique's size) and depth_range.z (its lookup bias); the rest is common.
  virtual void fill(shared::GpuShadow& record, const scene::ShadowSettings& settings, const LightView& view) const;

  virtual std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const;

  // After a completed frame: the light's capture counter words (0: segments asked
  // for, 1 and 2: what the build asked for) into `stats`. Returns true when the map must be
  // created again (it grew `state`).
  virtual bool finish_frame(const uint32_t counters[3], TechniqueMapState& state, LightShadowStats& stats) const;

  // GpuShadow::technique: the registry position + 1 (0 is kShadowNone), as the
  // generated GLSL dispatch numbers them.
  uint32_t code() const;
  // A parameter's value in `settings`, else its default.
  double parameter(const scene::ShadowSettings& settings, std::string_view name) const;
};

}  // namespace avsm::passes
