#include "passes/shadows/inspection/shadow_probe_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "gpu/transfer.h"

namespace avsm::passes {

ShadowProbePass::ShadowProbePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/inspection/shadow_probe.comp"), "shadow probes")) {}

void ShadowProbePass::upload_points(std::vector<glm::vec4> packed, uint32_t count, uint32_t light_count, Mode mode) {
  if (packed.empty()) packed.emplace_back(0.0f);  // a buffer cannot be empty
  point_count_ = count;
  light_count_ = light_count;
  mode_ = mode;
  points_ = gpu::create_buffer_from(ctx_, std::move(packed), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "probe points");
  results_.create(ctx_, {std::max<uint64_t>(uint64_t(point_count_) * light_count_, 1) * sizeof(float),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::HostReadback, "probe results"});
}

void ShadowProbePass::set_points(const std::vector<glm::vec3>& points, uint32_t light_count) {
  std::vector<glm::vec4> packed;
  for (const glm::vec3& p : points) packed.emplace_back(p, 1.0f);
  upload_points(std::move(packed), uint32_t(points.size()), light_count, Mode::points);
}

void ShadowProbePass::set_surface_points(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals,
                                         uint32_t light_count) {
  if (normals.size() != points.size())
    throw std::invalid_argument("ShadowProbePass: " + std::to_string(points.size()) + " surface points but " +
                                std::to_string(normals.size()) + " normals");
  std::vector<glm::vec4> packed;
  for (size_t i = 0; i < points.size(); ++i) {
    packed.emplace_back(points[i], 1.0f);
    packed.emplace_back(glm::normalize(normals[i]), 0.0f);
  }
  upload_points(std::move(packed), uint32_t(points.size()), light_count, Mode::surface_points);
}

void ShadowProbePass::set_texel_samples(const std::vector<TexelSample>& samples) {
  std::vector<glm::vec4> packed;  // x, y texel, z depth, w light: exact in floats at these sizes
  for (const TexelSample& s : samples) {
    if (s.texel.x > 16384 || s.texel.y > 16384)
      throw std::invalid_argument("ShadowProbePass: texel sample of light " + std::to_string(s.light) +
                                  " at texel (" + std::to_string(s.texel.x) + ", " + std::to_string(s.texel.y) +
                                  ") is out of range");
    packed.emplace_back(float(s.texel.x), float(s.texel.y), s.depth, float(s.light));
  }
  if (packed.empty()) packed.emplace_back(0.0f);
  point_count_ = uint32_t(samples.size());
  light_count_ = 1;  // results: two values per sample
  mode_ = Mode::texel_curves;
  points_ = gpu::create_buffer_from(ctx_, std::move(packed), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "texel samples");
  results_.create(ctx_, {std::max<uint64_t>(uint64_t(point_count_) * 2, 1) * sizeof(float),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::HostReadback,
                         "texel sample results"});
}

void ShadowProbePass::add_to_graph(rg::Graph& graph, ShadowInputs& shadows) {
  if (point_count_ == 0 || light_count_ == 0) return;
  struct Data {
    rg::BufferHandle results, page_requests;
  };
  const bool texels = mode_ == Mode::texel_curves;
  const std::string name = texels ? "shadow texel curves" : "shadow probes";
  rg::BufferHandle results = rg::vulkan::import(graph, texels ? "texel sample results" : "probe results",
                                                results_[shadows.frame_slot],
                                                rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  graph.add_pass<Data>(name, rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) {
        d.results = b.write(results, rg::Usage::StorageWrite);
        shadows.declare_reads(b);
        d.page_requests = shadows.page_requests = shadows.declare_page_requests(b);
      },
      [this, shadows](const Data& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.buffer("Points", points_).buffer("Results", c.buffer(d.results));
        shadows.bind(bindings, c);
        shadows.bind_page_requests(bindings, c, d.page_requests);
        bindings.push(c.cmd());
        pipeline_.push_constants(c.cmd(), shared::ShadowProbePush{point_count_, light_count_, uint32_t(mode_)});
        pipeline_.dispatch_threads(c.cmd(), point_count_);
      });
}

std::vector<TexelSampleResult> ShadowProbePass::texel_results(uint32_t slot) const {
  if (mode_ != Mode::texel_curves) return {};
  std::vector<TexelSampleResult> out(point_count_);
  if (point_count_) std::memcpy(out.data(), results_[slot].mapped(), out.size() * sizeof(TexelSampleResult));
  return out;
}

std::vector<std::vector<float>> ShadowProbePass::results(uint32_t slot) const {
  if (mode_ == Mode::texel_curves) return {};
  std::vector<std::vector<float>> out(light_count_, std::vector<float>(point_count_));
  const auto* values = static_cast<const float*>(results_[slot].mapped());
  for (uint32_t light = 0; light < light_count_; ++light)
    std::memcpy(out[light].data(), values + size_t(light) * point_count_, point_count_ * sizeof(float));
  return out;
}

}  // namespace avsm::passes
