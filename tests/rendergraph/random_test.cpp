// Thousands of random graphs (seeded, deterministic), each compiled in four modes and
// checked by the independent verifier; heap sizes are compared with the lower bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "mock_memory_model.h"
#include "plan_verifier.h"
#include "test_graphs.h"

namespace rg_test {
namespace random_test {  // one per file: test targets are unity builds
namespace {

using rg::QueueType;
using rg::Usage;

constexpr uint32_t kGraphCount = 3000;

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(engine_() % n); }  // same on every platform
  bool chance(uint32_t percent) { return below(100) < percent; }
  template <class T>
  const T& pick(const std::vector<T>& items) { return items[below(static_cast<uint32_t>(items.size()))]; }

 private:
  std::mt19937_64 engine_;
};

struct Slot {
  rg::ResourceKind kind;
  rg::TextureHandle texture;
  rg::BufferHandle buffer;
  bool readable;  // has contents: written, or imported with a defined state
};

std::vector<Usage> usages_for(QueueType queue, rg::ResourceKind kind, bool writes) {
  std::vector<Usage> usages;
  for (uint32_t i = 0; i < rg::kUsageCount; ++i) {
    const auto usage = static_cast<Usage>(i);
    if (rg::usage_problem(usage, queue, kind) == nullptr && rg::usage_info(usage, queue).is_write == writes)
      usages.push_back(usage);
  }
  return usages;
}

rg::TextureDesc random_texture(Rng& rng) {
  static const std::vector<uint32_t> sizes = {64, 128, 256, 512, 1024};
  static const std::vector<VkFormat> formats = {VK_FORMAT_R8_UNORM, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_UINT,
                                                VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_D32_SFLOAT};
  rg::TextureDesc desc = texture_desc(rng.pick(sizes), rng.pick(sizes), rng.pick(formats));
  if (rng.chance(20)) desc.mip_levels = 1 + rng.below(4);
  if (rng.chance(10)) desc.array_layers = 1 + rng.below(6);
  return desc;
}

rg::BufferDesc random_buffer(Rng& rng) { return {(uint64_t{1} << (6 + rng.below(18))) + rng.below(1000)}; }

rg::ImportState random_state(Rng& rng, rg::ResourceKind kind, bool initial) {
  const bool texture = kind == rg::ResourceKind::Texture;
  std::vector<rg::ImportState> states = {rg::ImportState::none(),
                                         rg::ImportState::of(Usage::Sampled, QueueType::Compute),
                                         rg::ImportState::of(Usage::StorageWrite, QueueType::Compute),
                                         rg::ImportState::of(Usage::TransferDst),
                                         rg::ImportState::of(Usage::TransferSrc)};
  if (texture) {
    states.push_back(rg::ImportState::of(Usage::Sampled));
    states.push_back(rg::ImportState::of(Usage::ColorAttachment));
    if (!initial) states.push_back(rg::ImportState::of(Usage::Present));
  } else {
    states.push_back(rg::ImportState::of(Usage::HostRead));
    states.push_back(rg::ImportState::of(Usage::UniformRead));
  }
  return rng.pick(states);
}

// `ranges` decides the buffer ranges on its own stream, so the graphs' structure (and the
// heap bounds measured below) are those of the generator without ranges.
void add_random_pass(rg::Graph& graph, Rng& rng, Rng& ranges, std::vector<Slot>& slots, uint32_t index) {
  static const std::vector<QueueType> queues = {QueueType::Graphics, QueueType::Graphics, QueueType::Compute,
                                                QueueType::Compute, QueueType::Transfer};
  const QueueType queue = rng.pick(queues);
  graph.add_pass(std::string("pass_").append(std::to_string(index)), queue, [&](rg::PassBuilder& b) {
    // Use up to 4 distinct existing resources.
    std::vector<uint32_t> chosen;
    for (uint32_t tries = rng.below(5); tries > 0 && !slots.empty(); --tries) {
      const uint32_t s = rng.below(static_cast<uint32_t>(slots.size()));
      if (std::find(chosen.begin(), chosen.end(), s) == chosen.end()) chosen.push_back(s);
    }
    for (uint32_t s : chosen) {
      Slot& slot = slots[s];
      const uint32_t op = slot.readable ? rng.below(4) : 3;  // 0,1 read; 2 read_write; 3 write
      const auto usages = usages_for(queue, slot.kind, op >= 2);
      if (usages.empty()) continue;
      const Usage usage = rng.pick(usages);
      const bool texture = slot.kind == rg::ResourceKind::Texture;
      // Buffers with contents: often a range of quarters, sometimes after a read of the
      // quarters before it (a mip chain's shape).
      rg::BufferRange range;
      if (!texture && slot.readable && ranges.chance(40)) {
        const uint64_t quarter = graph.resources()[slot.buffer.index].buffer.size / 4;
        const uint32_t first = ranges.below(4);
        range = {first * quarter, (1 + ranges.below(4 - first)) * quarter};
        const auto reads = usages_for(queue, slot.kind, false);
        if (first > 0 && !reads.empty() && ranges.chance(30))
          b.read(slot.buffer, ranges.pick(reads), {0, first * quarter});
      }
      if (op <= 1) {
        texture ? (void)b.read(slot.texture, usage) : (void)b.read(slot.buffer, usage, range);
      } else if (op == 2) {
        if (texture) slot.texture = b.read_write(slot.texture, usage);
        else slot.buffer = b.read_write(slot.buffer, usage, range);
      } else {
        if (texture) slot.texture = b.write(slot.texture, usage);
        else slot.buffer = b.write(slot.buffer, usage, range);
        slot.readable = true;
      }
    }
    // Create up to 2 transients; most are written at once.
    for (uint32_t created = rng.below(3); created > 0; --created) {
      const std::string name = std::string("t").append(std::to_string(slots.size()));
      Slot slot{rng.chance(50) ? rg::ResourceKind::Texture : rg::ResourceKind::Buffer, {}, {}, false};
      const auto usages = usages_for(queue, slot.kind, true);
      const bool write = !usages.empty() && rng.chance(85);
      if (slot.kind == rg::ResourceKind::Texture) {
        slot.texture = b.create_texture(name, random_texture(rng));
        if (write) slot.texture = b.write(slot.texture, rng.pick(usages));
      } else {
        slot.buffer = b.create_buffer(name, random_buffer(rng));
        if (write) slot.buffer = b.write(slot.buffer, rng.pick(usages));
      }
      slot.readable = write;
      slots.push_back(slot);
    }
    if (rng.chance(8)) b.side_effect();
  }, no_execute);
}

rg::Graph random_graph(uint64_t seed) {
  Rng rng(seed), ranges(seed ^ 0x9e3779b97f4a7c15ull);
  rg::Graph graph;
  std::vector<Slot> slots;
  for (uint32_t i = rng.below(4); i > 0; --i) {
    const std::string name = std::string("import_").append(std::to_string(slots.size()));
    Slot slot{rng.chance(60) ? rg::ResourceKind::Texture : rg::ResourceKind::Buffer, {}, {}, true};
    const rg::ImportState initial = random_state(rng, slot.kind, true);
    const rg::ImportState final_state = random_state(rng, slot.kind, false);
    if (slot.kind == rg::ResourceKind::Texture) {
      slot.texture = graph.import_texture(name, random_texture(rng), initial, final_state);
      slot.readable = initial.layout != VK_IMAGE_LAYOUT_UNDEFINED;
    } else {
      slot.buffer = graph.import_buffer(name, random_buffer(rng), initial, final_state);
    }
    slots.push_back(slot);
  }
  const uint32_t pass_count = 3 + rng.below(28);
  for (uint32_t p = 0; p < pass_count; ++p) add_random_pass(graph, rng, ranges, slots, p);
  for (const Slot& slot : slots) {
    if (!slot.readable || !rng.chance(10)) continue;
    if (slot.kind == rg::ResourceKind::Texture) graph.mark_output(slot.texture);
    else graph.mark_output(slot.buffer);
  }
  return graph;
}

// Largest sum of live transient bytes at any pass, per heap (= per memory class): no
// placement can do better, since everything alive at one pass needs disjoint memory.
uint64_t lower_bound(const rg::CompiledPlan& plan, uint32_t heap) {
  std::vector<uint64_t> live(plan.passes.size(), 0);
  for (const rg::PlannedResource& r : plan.resources)
    if (r.heap == heap)
      for (uint32_t q = r.first_pass; q <= r.last_pass; ++q) live[q] += r.size;
  return live.empty() ? 0 : *std::max_element(live.begin(), live.end());
}

TEST(RandomGraphs, PlansVerifyAndHeapsStayNearTheLowerBound) {
  const MockMemoryModel one_class;
  const MockMemoryModel two_classes({.split_render_targets = true, .granularity = 4096});
  const rg::CompileOptions modes[] = {{}, {.aliasing = false}, {.culling = false}, {.serial_full_barriers = true}};

  double worst_ratio = 1.0, total_heap = 0.0, total_bound = 0.0;
  uint64_t worst_seed = 0;
  int failures = 0;
  for (uint64_t seed = 1; seed <= kGraphCount && failures < 5; ++seed) {
    const rg::Graph graph = random_graph(seed);
    const MockMemoryModel& memory = seed % 2 ? one_class : two_classes;
    for (const rg::CompileOptions& options : modes) {
      const rg::CompiledPlan plan = graph.compile(memory, options);
      const auto problems = verify_plan(graph, plan, memory);
      if (!problems.empty()) {
        ++failures;
        ADD_FAILURE() << "seed " << seed << " (aliasing " << options.aliasing << ", culling " << options.culling
                      << ", serial " << options.serial_full_barriers << "): " << problems.front() << "\n"
                      << plan.to_text();
      }
      uint64_t unaliased = 0;
      for (const auto& r : plan.resources) unaliased += r.heap != rg::kInvalidIndex ? r.size : 0;
      EXPECT_EQ(plan.stats.transient_bytes_unaliased, unaliased);
      if (!options.aliasing || !options.culling) continue;

      uint64_t heap_bytes = 0, bound = 0;
      for (uint32_t h = 0; h < plan.heaps.size(); ++h) {
        const uint64_t heap_bound = lower_bound(plan, h);
        EXPECT_GE(plan.heaps[h].size, heap_bound) << "seed " << seed;
        heap_bytes += plan.heaps[h].size;
        bound += heap_bound;
      }
      if (bound == 0) continue;
      const double ratio = static_cast<double>(heap_bytes) / static_cast<double>(bound);
      total_heap += static_cast<double>(heap_bytes);
      total_bound += static_cast<double>(bound);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst_seed = seed;
      }
    }
  }
  std::printf("[ random   ] %u graphs x 4 modes verified; heap/lower bound: worst %.3f (seed %llu), overall %.3f\n",
              kGraphCount, worst_ratio, static_cast<unsigned long long>(worst_seed), total_heap / total_bound);
  // Bounds, measured: these 3000 seeds give worst 1.284 and overall 1.003; a run over
  // 30000 seeds gave worst 1.487, overall 1.003. The excess is fragmentation of greedy
  // placement on a few mixed-size, mixed-alignment resources (optimal placement is NP-hard);
  // the multi-light graphs land exactly on the bound. 1.5 / 1.02 catch regressions in
  // placement quality without depending on one seed.
  EXPECT_LE(worst_ratio, 1.5);
  EXPECT_LE(total_heap / total_bound, 1.02);
}

TEST(RandomGraphs, CompilationIsDeterministic) {
  const MockMemoryModel memory;
  for (uint64_t seed = 1; seed <= 200; ++seed) {
    const rg::Graph a = random_graph(seed), b = random_graph(seed);
    EXPECT_EQ(a.shape_hash(), b.shape_hash());
    EXPECT_EQ(a.compile(memory).to_text(), b.compile(memory).to_text()) << "seed " << seed;
  }
}

}  // namespace
}  // namespace random_test
}  // namespace rg_test
