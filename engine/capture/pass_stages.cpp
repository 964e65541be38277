#include "capture/pass_stages.h"

#include <cctype>
#include <cmath>

namespace avsm::capture {

namespace {

bool has(std::string_view text, std::string_view part) { return text.find(part) != std::string_view::npos; }
bool starts_with(std::string_view text, std::string_view start) { return text.substr(0, start.size()) == start; }

// A shadow map's passes are named "light <index>[ face|cascade|cluster <index>] <what>"
// (passes/shadows/shadow_maps.cpp).
bool is_light_pass(std::string_view name) {
  return starts_with(name, "light ") && name.size() > 6 && std::isdigit(static_cast<unsigned char>(name[6]));
}

PassStage light_pass_stage(std::string_view name) {
  // The fixed build's light depth image and hair bins stand where the lists' capture does.
  if (has(name, " capture ") || has(name, " clear lists") || has(name, " light depth") || has(name, " hair bins"))
    return PassStage::shadow_capture;
  if (has(name, " sort lists")) return PassStage::sort;
  if (has(name, " resolve") || has(name, " build") || has(name, " dsm clear")) return PassStage::build;
  if (has(name, " mips ")) return PassStage::mips;
  return PassStage::other;  // copy lists (for the viewer), debug image
}

}  // namespace

PassStage pass_stage(std::string_view name) {
  if (is_light_pass(name)) return light_pass_stage(name);
  // The camera's shading, with its hair lighting and volume lighting cache.
  if (name == "opaque" || name == "hair" || starts_with(name, "hair ") || name == "volumes" ||
      starts_with(name, "volume "))
    return PassStage::camera;
  return PassStage::other;  // shadow parameters, tonemap, shadow quality, probes, texel curves
}

std::string_view shadow_step(std::string_view name) {
  if (!is_light_pass(name)) return "";
  const size_t capture = name.find(" capture ");
  if (capture != std::string_view::npos) return name.substr(capture + 1);
  return to_string(light_pass_stage(name));
}

std::string_view to_string(PassStage stage) {
  switch (stage) {
    case PassStage::shadow_capture: return "shadow capture";
    case PassStage::sort: return "sort";
    case PassStage::build: return "resolve / build";
    case PassStage::mips: return "mips";
    case PassStage::camera: return "camera shading";
    case PassStage::other: return "other";
  }
  return "other";
}

bool is_inspection_pass(std::string_view name) {
  return name.ends_with(" debug image") || starts_with(name, "shadow probes") ||
         starts_with(name, "shadow texel curves") || starts_with(name, "shadow quality") ||
         name == "shadow resolution" || name == "shadow level overlay";
}

bool is_shadow_stage(PassStage stage) {
  return stage == PassStage::shadow_capture || stage == PassStage::sort || stage == PassStage::build ||
         stage == PassStage::mips;
}

StageTimes stage_gpu_ms(const TimingReport& timings) {
  StageTimes times{};
  for (const PassTiming& pass : timings.passes)
    if (std::isfinite(pass.gpu_ms.median)) times[size_t(pass_stage(pass.name))] += pass.gpu_ms.median;
  return times;
}

double shadow_gpu_ms(const StageTimes& stages) {
  double sum = 0;
  for (PassStage stage : kPassStages)
    if (is_shadow_stage(stage)) sum += stages[size_t(stage)];
  return sum;
}

}  // namespace avsm::capture
