#pragma once
// Dynamic rendering without the boilerplate: begin a render pass over whole
// targets and set the viewport and scissor to cover them.
#include <vulkan/vulkan.h>

#include <span>

namespace avsm::gpu {

struct ColorTarget {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  VkClearColorValue clear{};
  bool load = false;  // keep the contents instead of clearing
};

struct DepthTarget {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  float clear = 1.0f;
  bool store = false;      // keep depth after the pass
  bool read_only = false;  // test against existing depth: load it, write nothing (store op NONE)
};

// flip_y: a negative-height viewport, so +y in clip space points up (GL-style
// projection matrices from glm).
void begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, std::span<const ColorTarget> colors,
                     const DepthTarget* depth = nullptr, bool flip_y = false);

class Image;

// Clears a whole colour image (contents discarded, from UNDEFINED) with an empty
// render pass, leaving it in COLOR_ATTACHMENT_OPTIMAL. On lavapipe this also
// puts the driver in the state a real frame is in (see gpu_timer.h).
void clear_with_rendering(VkCommandBuffer cmd, const Image& target);

}  // namespace avsm::gpu
