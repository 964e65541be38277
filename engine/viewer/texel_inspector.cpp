#include "viewer/texel_inspector.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "capture/files.h"
#include "passes/shadows/shadow_maps.h"
#include "renderer/scene_picking.h"

namespace avsm::viewer {
namespace fs = std::filesystem;
using renderer::pick_point;
using renderer::PickedPoint;

namespace {

std::string format_point(const glm::vec3& p) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.3g, %.3g, %.3g)", p.x, p.y, p.z);
  return text;
}

// A curve for `light`'s texel, its samples evenly over the light's depth range
// (the same depths avsm-capture --plot-texel uses).
TexelCurve curve_for(const scene::Scene& scene, const passes::LightView& view, uint32_t light, glm::uvec2 texel) {
  TexelCurve curve;
  curve.light = light;
  curve.light_name = scene.lights[light].name;
  curve.technique = capture::technique_label(scene.lights[light].shadow);
  curve.texel = texel;
  curve.near_depth = view.near_depth;
  curve.far_depth = view.far_depth;
  for (uint32_t k = 0; k < capture::kCurveSamples; ++k)
    curve.depths.push_back(view.near_depth +
                           float(k) / float(capture::kCurveSamples - 1) * (view.far_depth - view.near_depth));
  return curve;
}

}  // namespace

float TexelCurve::max_difference() const {
  float gap = 0.0f;
  for (size_t i = 0; i < technique_values.size() && i < reference_values.size(); ++i)
    gap = std::max(gap, std::abs(technique_values[i] - reference_values[i]));
  return gap;
}

std::optional<glm::uvec2> light_texel(const passes::LightView& view, const glm::vec3& world) {
  const std::optional<glm::vec2> uv = view.uv(world);  // nullopt behind a spot light
  if (!uv || uv->x < 0.0f || uv->y < 0.0f || uv->x >= 1.0f || uv->y >= 1.0f) return std::nullopt;
  return glm::uvec2(*uv * float(view.resolution));
}

bool TexelInspector::inspect_pixel(const scene::Scene& scene, const passes::View& view, glm::vec2 pixel) {
  const std::optional<PickedPoint> picked = pick_point(scene, view, pixel);
  if (!picked) return false;
  target_ = Target{pixel, picked->world, 0, {}};
  curves_.clear();
  description_ = "pixel (" + std::to_string(int(pixel.x)) + ", " + std::to_string(int(pixel.y)) + "): " +
                 picked->what + " at " + format_point(picked->world);
  return true;
}

void TexelInspector::inspect_light_texel(uint32_t light, glm::uvec2 texel) {
  target_ = Target{std::nullopt, std::nullopt, light, texel};
  curves_.clear();
  description_ = "light " + std::to_string(light) + " texel (" + std::to_string(texel.x) + ", " +
                 std::to_string(texel.y) + ")";
}

void TexelInspector::clear() {
  target_.reset();
  curves_.clear();
  description_.clear();
}

std::vector<passes::TexelSample> TexelInspector::prepare(const scene::Scene& scene,
                                                         const std::vector<passes::LightView>& views) {
  curves_.clear();
  if (!target_) return {};
  const size_t lights = std::min(views.size(), scene.lights.size());
  if (target_->world) {
    for (uint32_t light = 0; light < lights; ++light) {
      const std::optional<glm::uvec2> texel = light_texel(views[light], *target_->world);
      if (!texel) continue;  // the point lies outside this light's map
      curves_.push_back(curve_for(scene, views[light], light, *texel));
      curves_.back().point_depth = views[light].depth(*target_->world);
    }
  } else if (target_->light < lights && target_->texel.x < views[target_->light].resolution &&
             target_->texel.y < views[target_->light].resolution) {
    curves_.push_back(curve_for(scene, views[target_->light], target_->light, target_->texel));
  }
  std::vector<passes::TexelSample> samples;
  for (const TexelCurve& curve : curves_)
    for (float depth : curve.depths) samples.push_back({curve.light, curve.texel, depth});
  return samples;
}

void TexelInspector::read_results(const std::vector<passes::TexelSampleResult>& results, gpu::Context& ctx,
                                  const passes::ShadowMaps& shadows, const scene::Scene& scene) {
  size_t next = 0;
  for (TexelCurve& curve : curves_) {
    if (next + curve.depths.size() > results.size()) return;  // not the frame these curves asked for
    curve.technique_values.clear();
    curve.reference_values.clear();
    const bool known = curve.light < shadows.light_count() && curve.light < scene.lights.size();
    curve.exact = known && shadows.has_reference(curve.light);
    for (size_t k = 0; k < curve.depths.size(); ++k, ++next) {
      curve.technique_values.push_back(results[next].technique);
      if (curve.exact) curve.reference_values.push_back(results[next].reference);
    }
    if (!known) continue;
    curve.nodes = capture::texel_nodes(ctx, shadows, curve.light, curve.texel.x, curve.texel.y);
    curve.level.reset();
    if (const auto paged = shadows.paged_texel(curve.light, curve.texel.x, curve.texel.y)) curve.level = paged->level;
  }
}

bool TexelInspector::has_values() const {
  return !curves_.empty() && std::all_of(curves_.begin(), curves_.end(), [](const TexelCurve& c) { return c.has_values(); });
}

void TexelInspector::write_json(const fs::path& path) const {
  nlohmann::json curves = nlohmann::json::array();
  for (const TexelCurve& c : curves_) {
    nlohmann::json nodes = nlohmann::json::array();
    for (const capture::CurveNode& n : c.nodes) nodes.push_back({n.depth, n.transmittance});
    curves.push_back({{"light", c.light},
                      {"light_name", c.light_name},
                      {"technique", c.technique},
                      {"texel", {c.texel.x, c.texel.y}},
                      {"point_depth", std::isnan(c.point_depth) ? nlohmann::json(nullptr) : nlohmann::json(c.point_depth)},
                      {"depth_range", {c.near_depth, c.far_depth}},
                      {"depths", c.depths},
                      {"technique_values", c.technique_values},
                      {"reference_values", c.reference_values},
                      {"exact", c.exact},
                      {"level", c.level ? nlohmann::json(*c.level) : nlohmann::json(nullptr)},
                      {"max_abs_difference", c.max_difference()},
                      {"nodes", nodes}});
  }
  nlohmann::json json = {{"description", description_}, {"curves", curves}};
  if (target_ && target_->pixel) json["pixel"] = {target_->pixel->x, target_->pixel->y};
  if (target_ && target_->world) json["point"] = {target_->world->x, target_->world->y, target_->world->z};
  capture::write_json(path, json, /*indent=*/1);
}

}  // namespace avsm::viewer
