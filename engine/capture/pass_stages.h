#pragma once
// The frame's passes grouped into the stages of a shadowed frame (the columns of the
// AVSM paper's cost table): what the sweep report and the technique bench sum per-pass
// GPU times into. Defined once here, by the names the passes give themselves
// (passes/*.cpp: "<light prefix> capture opaque", "opaque", ...).
#include <array>
#include <string_view>

#include "capture/frame_report.h"

namespace avsm::capture {

enum class PassStage {
  shadow_capture,  // per light: clearing and filling the capture lists, or the fixed build's depth and hair bins
  sort,            // per light: sorting the lists
  build,           // per light: the maps' resolve or build (AVSM resolve, DSM / OSM / FOM build, fixed builds)
  mips,            // per light: the maps' mip levels
  camera,          // the camera's shading: opaque, hair and volumes
  other,           // the rest: frame set-up, copies, tone mapping, debug images and measurements
};
inline constexpr size_t kPassStageCount = 6;
inline constexpr std::array<PassStage, kPassStageCount> kPassStages = {
    PassStage::shadow_capture, PassStage::sort, PassStage::build, PassStage::mips, PassStage::camera, PassStage::other};

PassStage pass_stage(std::string_view pass_name);
// "shadow capture", "sort", "resolve / build", "mips", "camera shading", "other".
std::string_view to_string(PassStage stage);
// A shadow pass's step, finer than its stage: "capture <caster kind>" (opaque, hair,
// smoke, ...) for the capture passes, else its stage's name ("shadow capture" for the
// lists' clears and the fixed build's depth and hair bins, "sort", "resolve / build",
// "mips"); "" for passes of no light.
std::string_view shadow_step(std::string_view pass_name);
// The shadow maps' own stages: capture, sort, build and mips.
bool is_shadow_stage(PassStage stage);
// A pass that only shows or measures the frame (light pictures, shadow probes, texel
// curves, quality): what a capture or the viewer adds to the frame a renderer draws.
bool is_inspection_pass(std::string_view pass_name);

// Per stage (indexed as kPassStages), its passes' median GPU ms summed.
using StageTimes = std::array<double, kPassStageCount>;
StageTimes stage_gpu_ms(const TimingReport& timings);
// The shadow stages' sum.
double shadow_gpu_ms(const StageTimes& stages);

}  // namespace avsm::capture
