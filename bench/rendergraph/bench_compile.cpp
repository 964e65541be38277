// bench_rendergraph_compile: how long Graph::compile takes as graphs grow, on a realistic
// generated frame: per light a capture -> sort -> resolve -> mips chain with transient
// head-pointer images, node buffers and sort scratch, resolving into a persistent map,
// then one shading pass that reads every map. Prints a table (median of several runs) and
// the transient memory with and without aliasing.
#include <rendergraph/rendergraph.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using rg::PassBuilder;
using rg::QueueType;
using rg::Usage;

void no_execute(rg::PassContext&) {}

// Device-like requirements: images 64 KiB aligned, buffers 256, one memory class.
class BenchMemoryModel : public rg::MemoryModel {
 public:
  rg::MemoryRequirements texture(const rg::TextureDesc& d, rg::UsageSet, const std::string&) const override {
    const uint64_t texel = d.format == VK_FORMAT_R16G16B16A16_SFLOAT ? 8 : d.format == VK_FORMAT_R8_UNORM ? 1 : 4;
    uint64_t bytes = 0;
    for (uint32_t mip = 0; mip < d.mip_levels; ++mip)
      bytes += uint64_t{std::max(1u, d.width >> mip)} * std::max(1u, d.height >> mip);
    bytes *= texel * d.array_layers * d.depth;
    return {(bytes + 65535) / 65536 * 65536, 65536, 0x1};
  }
  rg::MemoryRequirements buffer(const rg::BufferDesc& d, rg::UsageSet, const std::string&) const override {
    return {(d.size + 255) / 256 * 256, 256, 0x1};
  }
  uint64_t buffer_image_granularity() const override { return 1024; }
};

rg::TextureDesc texture(uint32_t w, uint32_t h, VkFormat format, uint32_t mips = 1) {
  rg::TextureDesc desc;
  desc.width = w;
  desc.height = h;
  desc.mip_levels = mips;
  desc.format = format;
  return desc;
}

constexpr uint32_t kFixedPasses = 5;  // depth, gbuffer, shade, bloom, tonemap
constexpr uint32_t kPassesPerLight = 4;

// A frame with exactly `pass_count` passes (>= kFixedPasses + kPassesPerLight).
rg::Graph build_frame(uint32_t pass_count) {
  const uint32_t lights = (pass_count - kFixedPasses) / kPassesPerLight;
  const uint32_t extra = pass_count - kFixedPasses - lights * kPassesPerLight;
  rg::Graph graph;
  auto swapchain = graph.import_texture(
      "swapchain", texture(1920, 1080, VK_FORMAT_B8G8R8A8_UNORM),
      rg::ImportState{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED},
      rg::ImportState::of(Usage::Present));

  rg::TextureHandle depth, albedo, normal, hdr, bloom;
  graph.add_pass("depth_prepass", QueueType::Graphics, [&](PassBuilder& b) {
    depth = b.write(b.create_texture("depth", texture(1920, 1080, VK_FORMAT_D32_SFLOAT)), Usage::DepthAttachmentWrite);
  }, no_execute);
  graph.add_pass("gbuffer", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(depth, Usage::DepthAttachmentRead);
    albedo = b.write(b.create_texture("albedo", texture(1920, 1080, VK_FORMAT_R8G8B8A8_UNORM)), Usage::ColorAttachment);
    normal = b.write(b.create_texture("normal", texture(1920, 1080, VK_FORMAT_R16G16B16A16_SFLOAT)),
                     Usage::ColorAttachment);
  }, no_execute);

  std::vector<rg::TextureHandle> maps;
  for (uint32_t i = 0; i < lights; ++i) {
    const std::string n = std::to_string(i);
    auto map = graph.import_texture("avsm_map_" + n, texture(512, 512, VK_FORMAT_R16G16B16A16_SFLOAT, 10),
                                    rg::ImportState::of(Usage::Sampled), rg::ImportState::of(Usage::Sampled));
    rg::TextureHandle head;
    rg::BufferHandle nodes;
    graph.add_pass("capture_" + n, QueueType::Graphics, [&](PassBuilder& b) {
      b.read(depth, Usage::Sampled);
      head = b.write(b.create_texture("head_" + n, texture(1024, 1024, VK_FORMAT_R32_UINT)), Usage::StorageReadWrite);
      nodes = b.write(b.create_buffer("nodes_" + n, {32u << 20}), Usage::StorageWrite);
    }, no_execute);
    graph.add_pass("sort_" + n, QueueType::Compute, [&](PassBuilder& b) {
      b.read(head, Usage::StorageRead);
      nodes = b.read_write(nodes, Usage::StorageReadWrite);
      b.write(b.create_buffer("sort_scratch_" + n, {8u << 20}), Usage::StorageReadWrite);
    }, no_execute);
    graph.add_pass("resolve_" + n, QueueType::Compute, [&](PassBuilder& b) {
      b.read(head, Usage::StorageRead);
      b.read(nodes, Usage::StorageRead);
      map = b.write(map, Usage::StorageWrite);
    }, no_execute);
    graph.add_pass("mips_" + n, QueueType::Compute, [&](PassBuilder& b) {
      map = b.read_write(map, Usage::StorageReadWrite);
    }, no_execute);
    maps.push_back(map);
  }

  graph.add_pass("shade", QueueType::Graphics, [&](PassBuilder& b) {
    for (const auto& map : maps) b.read(map, Usage::Sampled);
    b.read(albedo, Usage::Sampled);
    b.read(normal, Usage::Sampled);
    hdr = b.write(b.create_texture("hdr", texture(1920, 1080, VK_FORMAT_R16G16B16A16_SFLOAT)), Usage::ColorAttachment);
  }, no_execute);
  for (uint32_t i = 0; i < extra; ++i)  // pad to the exact pass count: in-place post effects
    graph.add_pass("post_" + std::to_string(i), QueueType::Compute, [&](PassBuilder& b) {
      hdr = b.read_write(hdr, Usage::StorageReadWrite);
    }, no_execute);
  graph.add_pass("bloom", QueueType::Compute, [&](PassBuilder& b) {
    b.read(hdr, Usage::Sampled);
    bloom = b.write(b.create_texture("bloom", texture(960, 540, VK_FORMAT_R16G16B16A16_SFLOAT, 5)), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("tonemap", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(hdr, Usage::Sampled);
    b.read(bloom, Usage::Sampled);
    swapchain = b.write(swapchain, Usage::ColorAttachment);
  }, no_execute);
  return graph;
}

template <class Fn>
double median_microseconds(int runs, Fn&& fn) {
  std::vector<double> times;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

double mib(uint64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

}  // namespace

int main() {
  const BenchMemoryModel memory;
  std::printf("rendergraph compile benchmark (median of runs; lights = capture/sort/resolve/mips chains)\n\n");
  std::printf("%6s %6s %9s %9s %12s %9s %11s %11s %14s %14s\n", "passes", "lights", "resources", "barriers",
              "compile us", "us/pass", "build us", "runs", "aliased MiB", "unaliased MiB");
  for (uint32_t passes : {10u, 50u, 100u, 250u, 500u, 1000u, 2000u}) {
    const int runs = passes <= 100 ? 201 : passes <= 500 ? 41 : 15;
    const rg::Graph graph = build_frame(passes);
    rg::CompiledPlan plan = graph.compile(memory);  // warm-up, and the numbers to print
    const double compile_us = median_microseconds(runs, [&] { plan = graph.compile(memory); });
    const double build_us = median_microseconds(runs, [&] { build_frame(passes); });
    std::printf("%6zu %6u %9zu %9u %12.1f %9.2f %11.1f %11d %14.1f %14.1f\n", plan.passes.size(),
                (passes - kFixedPasses) / kPassesPerLight, plan.resources.size(), plan.stats.barrier_count,
                compile_us, compile_us / static_cast<double>(passes), build_us, runs,
                mib(plan.stats.transient_bytes_aliased), mib(plan.stats.transient_bytes_unaliased));
  }
  return 0;
}
