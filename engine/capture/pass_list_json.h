#pragma once
// The shadow pass list (passes/shadows/shadow_pass_list.h) as JSON: what avsm-capture
// --dump-passes writes, for the author of a host's frame graph to read. Vulkan values
// by name ("COMPUTE_SHADER", "SHADER_STORAGE_WRITE", "GENERAL", "STORAGE_BUFFER");
// no handles, so the same scene and settings give the same file on any device.
#include <filesystem>
#include <string>

#include "passes/shadows/shadow_pass_list.h"

namespace avsm::capture {

std::string pass_list_json(const passes::ShadowPassList& list);
// Throws std::runtime_error naming the file when it cannot be written.
void write_pass_list(const std::filesystem::path& file, const passes::ShadowPassList& list);

}  // namespace avsm::capture
