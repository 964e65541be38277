#include "capture/capture.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/rendering.h"
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

// The frame the capture renders until scene loading and the AVSM passes land:
// an HDR scene pass and a tonemap pass, declared in the frame graph each frame.
class PreviewFrame {
 public:
  PreviewFrame(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, uint32_t width, uint32_t height)
      : ctx_(ctx), width_(width), height_(height) {
    gpu::ImageDesc hdr_desc;
    hdr_desc.width = width;
    hdr_desc.height = height;
    hdr_desc.format = kHdrFormat;
    hdr_desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    hdr_desc.name = "hdr color";
    hdr_ = gpu::Image::create(ctx, hdr_desc);
    gpu::ImageDesc ldr_desc = hdr_desc;
    ldr_desc.format = kLdrFormat;
    ldr_desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ldr_desc.name = "tonemapped";
    ldr_ = gpu::Image::create(ctx, ldr_desc);

    gpu::GraphicsPipelineDesc scene;
    scene.name = "preview scene";
    scene.vertex = shaders.load("shaders/preview/boxes.vert");
    scene.fragment = shaders.load("shaders/preview/boxes.frag");
    scene.color_formats = {kHdrFormat};
    scene.depth_format = kDepthFormat;
    scene.depth_test = scene.depth_write = true;
    scene.cull_mode = VK_CULL_MODE_BACK_BIT;
    scene_ = gpu::Pipeline::graphics(ctx, scene);
    tonemap_ = gpu::Pipeline::compute(ctx, shaders.load("shaders/preview/tonemap.comp"), "tonemap");
  }

  // Declares this frame's passes; the persistent output images are bound to `executor`.
  rg::Graph build(rg::vulkan::Executor& executor) {
    rg::Graph graph;
    rg::TextureDesc hdr_desc{width_, height_, 1, 1, 1, kHdrFormat};
    rg::TextureDesc ldr_desc{width_, height_, 1, 1, 1, kLdrFormat};
    rg::TextureDesc depth_desc{width_, height_, 1, 1, 1, kDepthFormat};
    // Both outputs are read back after the frame, hence TransferSrc as their final state.
    rg::TextureHandle hdr = graph.import_texture("hdr color", hdr_desc, rg::ImportState::none(),
                                                 rg::ImportState::of(rg::Usage::TransferSrc));
    rg::TextureHandle ldr = graph.import_texture("tonemapped", ldr_desc, rg::ImportState::none(),
                                                 rg::ImportState::of(rg::Usage::TransferSrc));
    executor.bind(hdr, hdr_);
    executor.bind(ldr, ldr_);

    struct Scene {
      rg::TextureHandle color, depth;
    };
    const Scene& scene = graph.add_pass<Scene>("scene", rg::QueueType::Graphics,
        [&](rg::PassBuilder& b, Scene& d) {
          d.color = b.write(hdr, rg::Usage::ColorAttachment);
          d.depth = b.write(b.create_texture("depth", depth_desc), rg::Usage::DepthAttachmentWrite);
        },
        [this](const Scene& d, rg::PassContext& c) { record_scene(c, d.color, d.depth); });
    struct Tonemap {
      rg::TextureHandle hdr, ldr;
    };
    graph.add_pass<Tonemap>("tonemap", rg::QueueType::Compute,
        [&](rg::PassBuilder& b, Tonemap& d) {
          d.hdr = b.read(scene.color, rg::Usage::StorageRead);
          d.ldr = b.write(ldr, rg::Usage::StorageWrite);
        },
        [this](const Tonemap& d, rg::PassContext& c) { record_tonemap(c, d.hdr, d.ldr); });
    return graph;
  }

  const gpu::Image& hdr() const { return hdr_; }
  const gpu::Image& ldr() const { return ldr_; }

 private:
  static constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kLdrFormat = VK_FORMAT_R8G8B8A8_UNORM;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  void record_scene(rg::PassContext& c, rg::TextureHandle color_target, rg::TextureHandle depth_target) {
    VkCommandBuffer cmd = c.cmd();
    gpu::ColorTarget color{c.view(color_target), c.layout(color_target), {{0.35f, 0.45f, 0.6f, 1.0f}}};
    gpu::DepthTarget depth{c.view(depth_target), c.layout(depth_target)};
    gpu::begin_rendering(cmd, {width_, height_}, {&color, 1}, &depth, /*flip_y=*/true);
    glm::mat4 view = glm::lookAt(glm::vec3(3.5f, 2.5f, 4.5f), glm::vec3(0, 0.4f, 0), glm::vec3(0, 1, 0));
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(45.0f), float(width_) / float(height_), 0.1f, 50.0f);
    scene_.bind(cmd);
    scene_.push_constants(cmd, ScenePush{projection * view, glm::vec4(glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f)), 0)});
    vkCmdDraw(cmd, 36 * 4, 1, 0, 0);
    vkCmdEndRendering(cmd);
  }

  void record_tonemap(rg::PassContext& c, rg::TextureHandle hdr, rg::TextureHandle ldr) {
    tonemap_.bind(c.cmd());
    gpu::Bindings(ctx_, tonemap_).image(0, c.view(hdr), c.layout(hdr)).image(1, c.view(ldr), c.layout(ldr)).push(c.cmd());
    tonemap_.push_constants(c.cmd(), 1.0f);
    tonemap_.dispatch_threads(c.cmd(), width_, height_);
  }

  gpu::Context& ctx_;
  uint32_t width_, height_;
  gpu::Image hdr_, ldr_;
  gpu::Pipeline scene_, tonemap_;
};

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << text;
}

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
  rg::vulkan::Executor executor(ctx, calibration.mode);
  VkCommandBuffer cmd = ctx.allocate_command_buffer("frame");
  std::map<std::string, PassSamples> samples;
  std::vector<std::string> pass_order;
  std::map<std::string, rg::QueueType> queues;
  std::vector<double> frame_gpu_ms, frame_wall_ms;

  for (uint32_t index = 0; index < options.frames; ++index) {
    auto start = std::chrono::steady_clock::now();
    rg::Graph graph = frame.build(executor);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    executor.record(graph, cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    ctx.submit_and_wait(cmd);
    double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    bool warm_up = index == 0 && options.frames > 1;
    if (options.progress)
      std::fprintf(stderr, "frame %u/%u: %.2f ms%s\n", index + 1, options.frames, wall, warm_up ? " (warm-up)" : "");
    if (warm_up) continue;
    double total = 0;
    for (const rg::vulkan::PassTiming& pass : executor.read_timings()) {
      if (!samples.count(pass.name)) pass_order.push_back(pass.name);
      samples[pass.name].gpu_ms.push_back(pass.gpu_ms);
      samples[pass.name].cpu_record_ms.push_back(pass.cpu_record_ms);
      queues[pass.name] = pass.queue;
      total += pass.gpu_ms;
    }
    frame_gpu_ms.push_back(total);
    frame_wall_ms.push_back(wall);
  }

  CaptureOutputs out{options.out_dir / "frame.png", options.out_dir / "frame.exr", options.out_dir / "timings.json"};
  io::write_png_raw(out.png, gpu::read_image(ctx, frame.ldr(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
  io::write_exr(out.exr, gpu::read_image(ctx, frame.hdr(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));

  nlohmann::json passes = nlohmann::json::array();
  for (const std::string& name : pass_order) {
    const PassSamples& s = samples[name];
    passes.push_back({{"name", name},
                      {"queue", rg::to_string(queues[name])},
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
  write_text(options.out_dir / "graph.json", executor.plan().to_json());
  write_text(options.out_dir / "graph.dot", executor.plan().to_dot());
  const rg::PlanStats& stats = executor.plan().stats;
  write_json(options.out_dir / "memory.json", {{"transient_bytes_aliased", stats.transient_bytes_aliased},
                                               {"transient_bytes_unaliased", stats.transient_bytes_unaliased},
                                               {"heaps", executor.plan().heaps.size()}});

  std::vector<gpu::ValidationMessage> messages = ctx.validation_log().take();
  if (!messages.empty()) throw std::runtime_error("validation reported problems: " + gpu::describe(messages));
  return out;
}

}  // namespace avsm::capture
