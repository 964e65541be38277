#pragma once
// Flicker (avsm-capture --flicker): how much the shadows change from one frame to the next
// where nothing but the camera moved. Maps fitted to the view, paged maps' levels and pages,
// and their filtering shimmer as the camera moves unless they are snapped and filtered; the
// exact shadows do not change at all. So the figure is taken at fixed surface points (the
// ones a grid of the first frame's pixels sees; their geometry cannot change), each light's
// transmittance looked up as the opaque pass does (SceneRenderer::set_surface_probes), and
// only in captures where the lights and casters hold still (their exact transmittance cannot
// change): |T(frame k) - T(frame k - 1)| per point and light, over the frames after the
// first (which may still be building pages), as the mean, 95th percentile and maximum.
// ΔL of a point is the change of its direct light: its transmittance change times the
// light's share of the scene's light, so lights are weighed as the image weighs them.
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "passes/frame/view.h"
#include "scene/scene.h"

namespace avsm::capture {

struct FlickerProbes {
  std::vector<glm::vec3> points, normals;
};

// The surface points under a grid of columns x rows pixels of `view` (pixel centres),
// where a mesh is hit (renderer/scene_picking.h), with the normals facing the camera.
FlickerProbes flicker_probes(const scene::Scene& scene, const passes::View& view, uint32_t columns, uint32_t rows);

struct LightFlicker {
  std::string light;
  double mean = 0.0, p95 = 0.0, max = 0.0;  // |ΔT| over points and frame pairs
  double share_over_tenth = 0.0;            // of those, the share above 0.1: a visible pop, not shimmer
};

struct FlickerReport {
  uint32_t points = 0;
  uint32_t frame_pairs = 0;  // consecutive pairs measured (after the first frame)
  uint32_t unfinished_frames = 0;  // left out, with the pairs they are in (see FlickerMeter::add_frame)
  double mean_delta_l = 0.0;  // mean over points and pairs of sum over lights of |ΔT| x the light's share
  std::vector<LightFlicker> lights;
};

class FlickerMeter {
 public:
  // `shares`: each light's share of the scene's light (summing to 1).
  FlickerMeter(std::vector<std::string> lights, std::vector<double> shares);
  // One frame's transmittance, [light][point] (SceneRenderer::probe_results()). An
  // `unfinished` frame (its maps dropped what did not fit: lighter shadows, and larger
  // buffers the next frame) is wrong for a known reason: its changes are left out, and
  // counted. Paged maps' pages still pending are not that: the coarser level a lookup falls
  // back to meanwhile is exactly what flickers.
  void add_frame(const std::vector<std::vector<float>>& transmittance, bool unfinished = false);
  FlickerReport report() const;

 private:
  std::vector<std::string> lights_;
  std::vector<double> shares_;
  uint32_t frames_ = 0, pairs_ = 0, unfinished_ = 0;
  bool previous_unfinished_ = false;
  std::vector<std::vector<float>> previous_;
  std::vector<std::vector<float>> changes_;  // per light, every |ΔT|
  std::vector<double> delta_l_;              // per point and pair
};

// Each light's share of the scene's light: its colour's luminance times its intensity,
// over the sum of them.
std::vector<double> light_shares(const scene::Scene& scene);

nlohmann::json to_json(const FlickerReport& report);

}  // namespace avsm::capture
