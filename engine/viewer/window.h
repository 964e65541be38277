#pragma once
// The viewer's window (GLFW, no client API: Vulkan draws into it) and its Vulkan
// surface. GLFW is started here and stopped with the window; only one exists at a time.
#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace avsm::viewer {

// The window or its surface could not be created (no display, no Vulkan WSI).
class WindowError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Window {
 public:
  // Opens a window of `width` x `height` screen coordinates. Throws WindowError with
  // GLFW's reason when there is no display or no Vulkan support.
  Window(const std::string& title, uint32_t width, uint32_t height);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  // What the Vulkan instance must enable to present to this window.
  std::vector<std::string> required_instance_extensions() const;
  VkExtent2D framebuffer_size() const;
  // Framebuffer pixels per screen coordinate (ImGui's DisplayFramebufferScale; 2 on a
  // HiDPI screen); 1 while the window has no size.
  glm::vec2 framebuffer_scale() const;
  bool should_close() const;
  void request_close();
  void set_title(const std::string& title);
  // Processes pending input; waits up to `timeout_seconds` for some when > 0.
  void poll_events(double timeout_seconds = 0.0);

 private:
  GLFWwindow* window_ = nullptr;
};

// A VkSurfaceKHR for a window, destroyed before the instance it belongs to.
class Surface {
 public:
  Surface(VkInstance instance, const Window& window);
  ~Surface();
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;
  VkSurfaceKHR handle() const { return surface_; }

 private:
  VkInstance instance_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

// Dear ImGui's context, fed with the window's input by ImGui's GLFW backend
// (installed before any other callback, so it sees every event).
class ImGuiWindowInput {
 public:
  explicit ImGuiWindowInput(const Window& window);
  ~ImGuiWindowInput();
  ImGuiWindowInput(const ImGuiWindowInput&) = delete;
  ImGuiWindowInput& operator=(const ImGuiWindowInput&) = delete;
  // Starts an ImGui frame with this frame's input.
  void new_frame();
};

}  // namespace avsm::viewer
