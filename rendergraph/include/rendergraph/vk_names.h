#pragma once
// Symbolic names for the Vulkan values the plan contains, for dumps, logs and messages:
// "COMPUTE_SHADER|FRAGMENT_SHADER", "SHADER_STORAGE_WRITE", "GENERAL", "R16G16B16A16_SFLOAT".
#include <vulkan/vulkan_core.h>

#include <string>

namespace rg {

std::string stage_names(VkPipelineStageFlags2 stages);  // "NONE" for 0
std::string access_names(VkAccessFlags2 access);        // "NONE" for 0
std::string layout_name(VkImageLayout layout);
std::string format_name(VkFormat format);

}  // namespace rg
