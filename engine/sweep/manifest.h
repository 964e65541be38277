#pragma once
// Sweep manifests: the JSON file that lists a sweep's jobs, as a cross product of
// scenes x resolutions x shadow settings and/or an explicit list (the format is in the
// docs/farm.md). Reading is strict, as scene files are: unknown
// keys, wrong types, unknown techniques, duplicate ids, a reference_job that does not
// exist and values out of range are scene::LoadErrors naming the file and the JSON path
// (e.g. "jobs[3].shadow.nodes: must be 4, 8, 12 or 16, got 7").
#include <filesystem>
#include <string_view>

#include "capture/capture.h"
#include "sweep/sweep_index.h"

namespace avsm::sweep {

constexpr int kManifestFormatVersion = 1;

// The sweep's jobs in manifest order (the cross product first, then "jobs"), each
// pending, with its settings, avsm-capture arguments and output folder (its id).
// Scene paths come back absolute, resolved against the manifest's folder.
SweepIndex read_manifest(const std::filesystem::path& file);
// The same from text; `file` names the manifest in messages and anchors relative paths.
SweepIndex parse_manifest(std::string_view json_text, const std::filesystem::path& file);

// What avsm-capture renders a job with (without an output folder).
capture::CaptureOptions capture_options(const JobSettings& settings);

}  // namespace avsm::sweep
