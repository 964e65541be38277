#include "viewer/window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>

#include <algorithm>

namespace avsm::viewer {

namespace {

// GLFW reports errors through a callback; the last one explains a failed call.
std::string last_glfw_error;

void remember_glfw_error(int code, const char* description) {
  last_glfw_error = description ? description : "GLFW error " + std::to_string(code);
}

std::string glfw_reason() { return last_glfw_error.empty() ? "unknown reason" : last_glfw_error; }

}  // namespace

Window::Window(const std::string& title, uint32_t width, uint32_t height) {
  glfwSetErrorCallback(remember_glfw_error);
  if (!glfwInit())
    throw WindowError("cannot open a window: " + glfw_reason() +
                      " (is a display available? headless machines can run under xvfb-run -a)");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw WindowError("cannot open a window: GLFW finds no Vulkan loader or surface support");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string reason = glfw_reason();
    glfwTerminate();
    throw WindowError("cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                      " window: " + reason);
  }
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::required_instance_extensions() const {
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) throw WindowError("GLFW cannot present with Vulkan here: " + glfw_reason());
  return {names, names + count};
}

VkExtent2D Window::framebuffer_size() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return {uint32_t(std::max(width, 0)), uint32_t(std::max(height, 0))};
}

glm::vec2 Window::framebuffer_scale() const {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  const VkExtent2D framebuffer = framebuffer_size();
  if (width <= 0 || height <= 0 || framebuffer.width == 0 || framebuffer.height == 0) return glm::vec2(1.0f);
  return glm::vec2(float(framebuffer.width) / float(width), float(framebuffer.height) / float(height));
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }
void Window::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

void Window::poll_events(double timeout_seconds) {
  if (timeout_seconds > 0.0)
    glfwWaitEventsTimeout(timeout_seconds);
  else
    glfwPollEvents();
}

Surface::Surface(VkInstance instance, const Window& window) : instance_(instance) {
  const VkResult result = glfwCreateWindowSurface(instance, window.handle(), nullptr, &surface_);
  if (result != VK_SUCCESS)
    throw WindowError("cannot create a Vulkan surface for the window (VkResult " + std::to_string(int(result)) +
                      "): " + glfw_reason());
}

Surface::~Surface() { vkDestroySurfaceKHR(instance_, surface_, nullptr); }

ImGuiWindowInput::ImGuiWindowInput(const Window& window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to wherever the viewer was started
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window.handle(), /*install_callbacks=*/true);
}

ImGuiWindowInput::~ImGuiWindowInput() {
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiWindowInput::new_frame() {
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

}  // namespace avsm::viewer
