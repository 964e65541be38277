#pragma once
// Shadow quality against the exact reference, on the CPU side of avsm-capture:
//  - --compare-to uncompressed: the per-pixel errors of passes/camera/quality/shadow_quality_pass.h
//    summed up per light into quality.json, and light<i>_error.png per light;
//  - --plot-texel LIGHT:X,Y: one texel's transmittance curve, technique over the
//    exact curve, as curve_<light index>_<x>_<y>.svg (like Figures 6-7 of the AVSM paper).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "passes/shadows/light_view.h"
#include "passes/shadows/inspection/shadow_probe_pass.h"
#include "passes/camera/quality/shadow_quality_hair_pass.h"
#include "passes/camera/quality/shadow_quality_pass.h"
#include "scene/scene.h"

namespace avsm::gpu {
class Context;
}
namespace avsm::passes {
class ShadowMaps;
}

namespace avsm::capture {

// Writes a width x height PNG; `colour` sets pixel y * width + x's RGB (row 0 at the top).
void write_pixel_image(const std::filesystem::path& path, uint32_t width, uint32_t height,
                       const std::function<void(size_t pixel, float* rgb)>& colour);
// Pixels with no receiver for the light: a dim blue, told apart from black (error 0).
inline constexpr float kNoReceiverColour[3] = {0.08f, 0.1f, 0.22f};

// A light's name in the figures: its own, or "light <index>".
std::string light_label(const scene::Scene& scene, size_t index);

// ---- quality.json ----

// Errors are shown this many times larger in light<i>_error.png (as in the paper's figures), clamped to 1.
inline constexpr float kErrorImageScale = 4.0f;

// What quality.json and report.html say the error images' colours and each receiver kind are.
extern const char* const kErrorImageColours;
std::string surface_receivers_rule();
std::string smoke_receivers_rule();
std::string hair_receivers_rule();

struct ErrorStats {
  uint64_t receivers = 0;
  double sum = 0.0;  // of |T - T_ref|
  double max = 0.0;
  double mean() const { return receivers ? sum / double(receivers) : 0.0; }
  void add(const ErrorStats& other);
};

struct LightQuality {
  std::string light;  // name, or "light <i>"
  scene::ShadowSettings settings;
  ErrorStats surface, smoke, hair;
  ErrorStats all() const;
};

// The errors at the hair the camera sees (ShadowQualityHairPass::results()):
// [light * receivers + receiver], negative where a strand vertex is not a receiver.
struct HairErrors {
  std::vector<float> errors;
  uint32_t receivers = 0;
};

// Sums the per-pixel errors (ShadowQualityPass::results(), `light_count` lights of a
// width x height image) and the hair errors per light.
std::vector<LightQuality> summarize_quality(const std::vector<passes::PixelShadowError>& errors, uint32_t width,
                                            uint32_t height, const scene::Scene& scene, const HairErrors& hair = {});

// quality.json: every light's errors over a width x height frame (to_json in capture/frame_report.h).
struct QualityReport {
  uint32_t width = 0, height = 0;
  std::vector<LightQuality> lights;  // light i's error image: error_image_name(i)
};
std::string error_image_name(size_t light);  // light<i>_error.png

// Writes quality.json and light<i>_error.png into out_dir; returns what quality.json holds.
QualityReport write_quality(const std::filesystem::path& out_dir, const scene::Scene& scene,
                                    const std::vector<passes::PixelShadowError>& errors, uint32_t width,
                                    uint32_t height, const HairErrors& hair = {});

// ---- texel curves ----

inline constexpr uint32_t kCurveSamples = 512;  // depths per curve

struct TexelPlot {
  std::string spec;   // the flag value as given, LIGHT:X,Y (for messages)
  std::string light;  // light index or name
  uint32_t x = 0, y = 0;
  uint32_t light_index = 0;  // resolved by resolve_texel_plots()

  bool operator==(const TexelPlot&) const = default;
};

// Parses LIGHT:X,Y (LIGHT: index or name, may itself hold ':'; X, Y whole numbers);
// nullopt when malformed.
std::optional<TexelPlot> parse_texel_plot(const std::string& spec);

// Finds each plot's light (index first, then name) and checks the texel lies in
// its level-0 map. Throws std::runtime_error naming the flag value otherwise.
void resolve_texel_plots(std::vector<TexelPlot>& plots, const scene::Scene& scene);

// kCurveSamples samples per plot, evenly over its light's depth range (near to far depth).
std::vector<passes::TexelSample> texel_curve_samples(const std::vector<TexelPlot>& plots,
                                                     const std::vector<passes::LightView>& views);

// "AVSM-8", "OSM-32", "DSM (error 0.01)", "uncompressed": what legends and quality.json
// call a light's technique (its ShadowTechnique::label()).
std::string technique_label(const scene::ShadowSettings& settings);

// One stored node of a texel's AVSM curve.
struct CurveNode {
  float depth, transmittance;
};

// The stored AVSM nodes of light `light`'s level-0 texel (x, y), read back from its
// map now (padding repeats of the last node dropped); none unless its technique stores
// AVSM nodes.
std::vector<CurveNode> texel_nodes(gpu::Context& ctx, const passes::ShadowMaps& shadows, uint32_t light, uint32_t x,
                                   uint32_t y);

// Writes curve_<light>_<x>_<y>.svg per plot from the samples' results (same order as
// texel_curve_samples()); reads the AVSM nodes of each texel from `shadows` to mark
// them. Returns the files written.
std::vector<std::filesystem::path> write_texel_curves(const std::filesystem::path& out_dir,
                                                      const std::vector<TexelPlot>& plots, const scene::Scene& scene,
                                                      const passes::ShadowMaps& shadows, gpu::Context& ctx,
                                                      const std::vector<passes::TexelSampleResult>& results);

}  // namespace avsm::capture
