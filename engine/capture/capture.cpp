#include "capture/capture.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <nlohmann/json.hpp>

#include "gpu/barriers.h"
#include "gpu/context.h"
#include "gpu/gpu_timer.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "gpu/transfer.h"
#include "gpu/vk_check.h"
#include "io/image_io.h"

namespace avsm::capture {
namespace fs = std::filesystem;

namespace {

struct ScenePush {
  glm::mat4 view_projection;
  glm::vec4 light_direction;
};

// Timings of one pass over all measured frames.
struct PassSamples {
  std::vector<double> gpu_ms;
  std::vector<double> cpu_record_ms;
};

struct Stats {
  double min = 0, median = 0, max = 0;
};

Stats stats_of(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2], values.back()};
}

nlohmann::json to_json(const Stats& s) { return {{"min", s.min}, {"median", s.median}, {"max", s.max}}; }

// The frame the capture renders until scene loading and the frame graph land:
// an HDR scene pass and a tonemap pass.
class PreviewFrame {
 public:
  PreviewFrame(const gpu::Context& ctx, const gpu::ShaderLibrary& shaders, uint32_t width, uint32_t height)
      : ctx_(ctx), width_(width), height_(height) {
    gpu::ImageDesc hdr_desc;
    hdr_desc.width = width;
    hdr_desc.height = height;
    hdr_desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    hdr_desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    hdr_desc.name = "hdr color";
    hdr_ = gpu::Image::create(ctx, hdr_desc);
    gpu::ImageDesc depth_desc = hdr_desc;
    depth_desc.format = VK_FORMAT_D32_SFLOAT;
    depth_desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    depth_desc.name = "depth";
    depth_ = gpu::Image::create(ctx, depth_desc);
    gpu::ImageDesc ldr_desc = hdr_desc;
    ldr_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    ldr_desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ldr_desc.name = "tonemapped";
    ldr_ = gpu::Image::create(ctx, ldr_desc);

    gpu::GraphicsPipelineDesc scene;
    scene.name = "preview scene";
    scene.vertex = shaders.load("shaders/preview/boxes.vert");
    scene.fragment = shaders.load("shaders/preview/boxes.frag");
    scene.color_formats = {hdr_desc.format};
    scene.depth_format = depth_desc.format;
    scene.depth_test = scene.depth_write = true;
    scene.cull_mode = VK_CULL_MODE_BACK_BIT;
    scene_ = gpu::Pipeline::graphics(ctx, scene);
    tonemap_ = gpu::Pipeline::compute(ctx, shaders.load("shaders/preview/tonemap.comp"), "tonemap");
  }

  // Records the frame; each pass is labelled and timed.
  void record(VkCommandBuffer cmd, gpu::GpuTimer& timer, std::map<std::string, double>& cpu_ms) {
    timer.begin_frame(cmd);
    time_pass(cmd, timer, cpu_ms, "scene", [&] { record_scene(cmd); });
    time_pass(cmd, timer, cpu_ms, "tonemap", [&] { record_tonemap(cmd); });
  }

  const gpu::Image& hdr() const { return hdr_; }
  const gpu::Image& ldr() const { return ldr_; }

 private:
  template <class Fn>
  void time_pass(VkCommandBuffer cmd, gpu::GpuTimer& timer, std::map<std::string, double>& cpu_ms,
                 const std::string& name, Fn&& fn) {
    auto start = std::chrono::steady_clock::now();
    gpu::ScopedLabel label(ctx_, cmd, name);
    uint32_t scope = timer.begin_scope(cmd, name);
    fn();
    timer.end_scope(cmd, scope);
    cpu_ms[name] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  void record_scene(VkCommandBuffer cmd) {
    gpu::image_barrier(cmd, hdr_.handle(), hdr_.full_range(), VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                       {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE},
                       gpu::kColorWrite);
    gpu::image_barrier(cmd, depth_.handle(), depth_.full_range(), VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                       {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_2_NONE},
                       {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT});
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = hdr_.view();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.clearValue.color = {{0.35f, 0.45f, 0.6f, 1.0f}};
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depth_.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {width_, height_}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);
    // Vulkan clip space has y down; flip the viewport so +y is up.
    VkViewport viewport{0, float(height_), float(width_), -float(height_), 0, 1};
    VkRect2D scissor{{0, 0}, {width_, height_}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    glm::mat4 view = glm::lookAt(glm::vec3(3.5f, 2.5f, 4.5f), glm::vec3(0, 0.4f, 0), glm::vec3(0, 1, 0));
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(45.0f), float(width_) / float(height_), 0.1f, 50.0f);
    scene_.bind(cmd);
    scene_.push_constants(cmd, ScenePush{projection * view, glm::vec4(glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f)), 0)});
    vkCmdDraw(cmd, 36 * 4, 1, 0, 0);
    vkCmdEndRendering(cmd);
  }

  void record_tonemap(VkCommandBuffer cmd) {
    gpu::image_barrier(cmd, hdr_.handle(), hdr_.full_range(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                       VK_IMAGE_LAYOUT_GENERAL, gpu::kColorWrite,
                       {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT});
    gpu::image_barrier(cmd, ldr_.handle(), ldr_.full_range(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                       {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE}, gpu::kComputeWrite);
    tonemap_.bind(cmd);
    gpu::Bindings(ctx_, tonemap_)
        .image(0, hdr_.view(), VK_IMAGE_LAYOUT_GENERAL)
        .image(1, ldr_.view(), VK_IMAGE_LAYOUT_GENERAL)
        .push(cmd);
    tonemap_.push_constants(cmd, 1.0f);
    tonemap_.dispatch_threads(cmd, width_, height_);
  }

  const gpu::Context& ctx_;
  uint32_t width_, height_;
  gpu::Image hdr_, depth_, ldr_;
  gpu::Pipeline scene_, tonemap_;
};

void write_json(const fs::path& path, const nlohmann::json& json) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << json.dump(2) << "\n";
}

}  // namespace

CaptureOutputs run_capture(const CaptureOptions& options) {
  if (options.width == 0 || options.height == 0 || options.width > 16384 || options.height > 16384)
    throw std::runtime_error("image size must be between 1 and 16384 pixels per side");
  if (options.frames == 0) throw std::runtime_error("--frames must be at least 1");
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) throw std::runtime_error(options.out_dir.string() + ": cannot create output folder: " + ec.message());

  gpu::ContextDesc desc;
  desc.app_name = "avsm-capture";
  desc.validation = options.validation;
  desc.device = options.device;
  desc.echo_validation = true;
  gpu::Context ctx(desc);
  gpu::ShaderLibrary shaders;
  gpu::TimestampCalibration calibration = gpu::calibrate_timestamps(ctx, shaders);
  if (options.progress)
    std::fprintf(stderr, "avsm-capture: %s (%s), timestamps %s\n", ctx.info().name.c_str(),
                 ctx.info().driver_info.c_str(), gpu::to_string(calibration.mode));

  PreviewFrame frame(ctx, shaders, options.width, options.height);
  gpu::GpuTimer timer(ctx, 64, calibration.mode);
  VkCommandBuffer cmd = ctx.allocate_command_buffer("frame");
  std::map<std::string, PassSamples> samples;
  std::vector<std::string> pass_order;
  std::vector<double> frame_gpu_ms, frame_wall_ms;

  for (uint32_t index = 0; index < options.frames; ++index) {
    std::map<std::string, double> cpu_ms;
    auto start = std::chrono::steady_clock::now();
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    frame.record(cmd, timer, cpu_ms);
    VK_CHECK(vkEndCommandBuffer(cmd));
    ctx.submit_and_wait(cmd);
    double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::vector<gpu::ScopeTiming> scopes = timer.read_scopes();
    bool warm_up = index == 0 && options.frames > 1;
    if (options.progress)
      std::fprintf(stderr, "frame %u/%u: %.2f ms%s\n", index + 1, options.frames, wall, warm_up ? " (warm-up)" : "");
    if (warm_up) continue;
    double total = 0;
    for (const gpu::ScopeTiming& scope : scopes) {
      if (!samples.count(scope.name)) pass_order.push_back(scope.name);
      samples[scope.name].gpu_ms.push_back(scope.gpu_ms);
      samples[scope.name].cpu_record_ms.push_back(cpu_ms[scope.name]);
      total += scope.gpu_ms;
    }
    frame_gpu_ms.push_back(total);
    frame_wall_ms.push_back(wall);
  }

  CaptureOutputs out{options.out_dir / "frame.png", options.out_dir / "frame.exr", options.out_dir / "timings.json"};
  io::write_png_raw(out.png, gpu::read_image(ctx, frame.ldr(), VK_IMAGE_LAYOUT_GENERAL));
  io::write_exr(out.exr, gpu::read_image(ctx, frame.hdr(), VK_IMAGE_LAYOUT_GENERAL));

  nlohmann::json passes = nlohmann::json::array();
  for (const std::string& name : pass_order) {
    const PassSamples& s = samples[name];
    passes.push_back({{"name", name},
                      {"queue", name == "tonemap" ? "compute" : "graphics"},
                      {"gpu_ms", to_json(stats_of(s.gpu_ms))},
                      {"cpu_record_ms", to_json(stats_of(s.cpu_record_ms))}});
  }
  nlohmann::json timings = {
      {"device", ctx.info().name},
      {"driver", ctx.info().driver_name + " " + ctx.info().driver_info},
      {"timestamp_mode", gpu::to_string(calibration.mode)},
      {"width", options.width},
      {"height", options.height},
      {"frames_measured", frame_gpu_ms.size()},
      {"passes", passes},
      {"frame_gpu_ms", to_json(stats_of(frame_gpu_ms))},
      {"frame_wall_ms", to_json(stats_of(frame_wall_ms))},
  };
  write_json(out.timings, timings);

  std::vector<gpu::ValidationMessage> messages = ctx.validation_log().take();
  if (!messages.empty()) throw std::runtime_error("validation reported problems: " + gpu::describe(messages));
  return out;
}

}  // namespace avsm::capture
