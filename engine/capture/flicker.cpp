#include "capture/flicker.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "renderer/scene_picking.h"

namespace avsm::capture {

FlickerProbes flicker_probes(const scene::Scene& scene, const passes::View& view, uint32_t columns, uint32_t rows) {
  FlickerProbes probes;
  for (uint32_t row = 0; row < rows; ++row)
    for (uint32_t column = 0; column < columns; ++column) {
      // The centre of the grid cell, in pixel_ray's pixel coordinates (it adds the half pixel).
      const glm::vec2 pixel((float(column) + 0.5f) * float(view.width) / float(columns) - 0.5f,
                            (float(row) + 0.5f) * float(view.height) / float(rows) - 0.5f);
      const std::optional<renderer::PickedPoint> hit = renderer::pick_point(scene, view, pixel);
      if (!hit || hit->normal == glm::vec3(0.0f)) continue;  // the sky, or inside a volume
      probes.points.push_back(hit->world);
      probes.normals.push_back(hit->normal);
    }
  return probes;
}

std::vector<double> light_shares(const scene::Scene& scene) {
  std::vector<double> shares;
  for (const scene::Light& light : scene.lights)
    shares.push_back(double(glm::dot(light.color, glm::vec3(0.2126f, 0.7152f, 0.0722f))) * double(light.intensity));
  const double total = std::accumulate(shares.begin(), shares.end(), 0.0);
  for (double& share : shares) share = total > 0.0 ? share / total : 1.0 / double(shares.size());
  return shares;
}

FlickerMeter::FlickerMeter(std::vector<std::string> lights, std::vector<double> shares)
    : lights_(std::move(lights)), shares_(std::move(shares)), changes_(lights_.size()) {
  if (shares_.size() != lights_.size()) throw std::invalid_argument("FlickerMeter: one share per light");
}

void FlickerMeter::add_frame(const std::vector<std::vector<float>>& transmittance, bool unfinished) {
  if (transmittance.size() != lights_.size())
    throw std::invalid_argument("FlickerMeter: " + std::to_string(transmittance.size()) + " lights' probes for " +
                                std::to_string(lights_.size()) + " lights");
  // The first frame is kept apart (a paged map may still be building its pages there).
  if (unfinished) ++unfinished_;
  if (++frames_ > 2 && !unfinished && !previous_unfinished_) {
    ++pairs_;
    const std::size_t points = transmittance.empty() ? 0 : transmittance[0].size();
    for (std::size_t p = 0; p < points; ++p) {
      double delta_l = 0.0;
      for (std::size_t l = 0; l < lights_.size(); ++l) {
        const float change = std::abs(transmittance[l][p] - previous_[l][p]);
        changes_[l].push_back(change);
        delta_l += double(change) * shares_[l];
      }
      delta_l_.push_back(delta_l);
    }
  }
  previous_ = transmittance;
  previous_unfinished_ = unfinished;
}

FlickerReport FlickerMeter::report() const {
  FlickerReport report;
  report.points = previous_.empty() ? 0 : uint32_t(previous_[0].size());
  report.frame_pairs = pairs_;
  report.unfinished_frames = unfinished_;
  if (!delta_l_.empty())
    report.mean_delta_l = std::accumulate(delta_l_.begin(), delta_l_.end(), 0.0) / double(delta_l_.size());
  for (std::size_t l = 0; l < lights_.size(); ++l) {
    LightFlicker light{lights_[l]};
    std::vector<float> sorted = changes_[l];
    if (!sorted.empty()) {
      std::sort(sorted.begin(), sorted.end());
      light.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / double(sorted.size());
      light.p95 = sorted[std::min(sorted.size() - 1, std::size_t(0.95 * double(sorted.size())))];
      light.max = sorted.back();
      const auto pops = sorted.end() - std::upper_bound(sorted.begin(), sorted.end(), 0.1f);
      light.share_over_tenth = double(pops) / double(sorted.size());
    }
    report.lights.push_back(light);
  }
  return report;
}

nlohmann::json to_json(const FlickerReport& report) {
  nlohmann::json lights = nlohmann::json::array();
  for (const LightFlicker& light : report.lights)
    lights.push_back({{"light", light.light}, {"mean_abs_dt", light.mean}, {"p95_abs_dt", light.p95}, {"max_abs_dt", light.max},
                      {"share_over_0_1", light.share_over_tenth}});
  return {{"points", report.points}, {"frame_pairs", report.frame_pairs},
          {"unfinished_frames_left_out", report.unfinished_frames}, {"mean_delta_l", report.mean_delta_l},
          {"lights", lights}};
}

}  // namespace avsm::capture
