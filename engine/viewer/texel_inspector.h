#pragma once
// Texel inspection: the user clicks a pixel (or a texel of a light's map), and for
// each light the inspector follows the light ray through the point under that
// pixel: which level-0 texel of the light's map it falls in, and that texel's
// transmittance curve over the light's whole depth range, for the light's technique
// and for the exact (uncompressed) curve, evaluated by the renderer's texel-curve
// probes (passes/shadows/inspection/shadow_probe_pass.h; needs ShadowOptions::keep_reference).
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "capture/quality.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/inspection/shadow_probe_pass.h"
#include "passes/frame/view.h"
#include "scene/scene.h"

namespace avsm::gpu {
class Context;
}
namespace avsm::passes {
class ShadowMaps;
}

namespace avsm::viewer {

struct TexelCurve {
  uint32_t light = 0;
  std::string light_name, technique;  // technique: capture::technique_label
  glm::uvec2 texel{0};
  float point_depth = NAN;  // the picked point's light depth; NaN when a texel was picked directly
  float near_depth = 0, far_depth = 1;
  std::vector<float> depths;  // capture::kCurveSamples, near to far
  std::vector<float> technique_values, reference_values;  // empty until a frame evaluated them
  std::vector<capture::CurveNode> nodes;                  // AVSM lights: the texel's stored nodes
  // False for paged lights: their pages keep no capture lists, so no exact curve
  // (reference_values stay empty). A paged light's curve is that of the finest resident
  // level over the texel: `level`.
  bool exact = true;
  std::optional<uint32_t> level;
  bool has_values() const { return !technique_values.empty(); }
  float max_difference() const;  // max |technique - reference| over the samples
};

// The level-0 texel of `view`'s map that `world` falls in; nullopt outside the map.
std::optional<glm::uvec2> light_texel(const passes::LightView& view, const glm::vec3& world);

class TexelInspector {
 public:
  // Inspects the point under `pixel` (x right, y down, in the view's pixels).
  // Returns false, and inspects nothing, when no surface or volume is there.
  bool inspect_pixel(const scene::Scene& scene, const passes::View& view, glm::vec2 pixel);
  // Inspects one texel of one light's map directly.
  void inspect_light_texel(uint32_t light, glm::uvec2 texel);
  void clear();
  bool active() const { return target_.has_value(); }

  // The texel samples to render with, for the lights as they are now (a light that
  // moved puts the picked point in another texel). Forgets earlier values.
  std::vector<passes::TexelSample> prepare(const scene::Scene& scene, const std::vector<passes::LightView>& views);
  // Takes the values of a frame rendered with prepare()'s samples (same order),
  // and the AVSM nodes of each texel.
  void read_results(const std::vector<passes::TexelSampleResult>& results, gpu::Context& ctx,
                    const passes::ShadowMaps& shadows, const scene::Scene& scene);

  const std::vector<TexelCurve>& curves() const { return curves_; }
  bool has_values() const;
  // "pixel (120, 80): mesh 'floor' at (0.1, 0, 2.3)" or "light 1 texel (10, 20)".
  const std::string& description() const { return description_; }
  // inspect.json: the description, the picked point, and every curve with its samples.
  void write_json(const std::filesystem::path& path) const;

 private:
  struct Target {
    std::optional<glm::vec2> pixel;
    std::optional<glm::vec3> world;  // the picked point (pixel inspection)
    uint32_t light = 0;              // direct texel inspection
    glm::uvec2 texel{0};
  };
  std::optional<Target> target_;
  std::vector<TexelCurve> curves_;
  std::string description_;
};

}  // namespace avsm::viewer
