// The AVSM shadow passes on the device, inside a frame graph, under validation:
//  - AvsmResolvePass against the C++ core (passes/shadows/techniques/avsm/avsm_core.h) run over the same lists,
//    node by node, and exact where the node budget holds the whole curve;
//  - AvsmMipsPass against the CPU mip chain (avsm_mip_merge), with odd sizes;
//  - the sort on lists of up to 20,000 segments beside short ones, against the CPU;
//  - a sorted resolve of the default scene bit-identical from run to run, and every
//    texel of its 32^2 AVSM-16 maps (lists read back) bit for bit against the core;
//  - the uncompressed (and a 16-node AVSM) lookup through a constant box against the
//    closed-form Beer-Lambert transmittance, via the probe pass;
//  - capture overflow: detected, reported, clamped to the limit, grown when allowed;
//  - the fixed build against sorted lists, across runs, with more hair layers, and
//    texel by texel against a CPU reference of it on random hair and meshes.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "passes/shadows/shadow_settings.h"
#include "gpu/context.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "passes/shadows/techniques/avsm/avsm_core.h"
#include "passes/shadows/techniques/avsm_map_layout.h"
#include "passes/shadows/techniques/avsm/avsm_mips_pass.h"
#include "passes/shadows/techniques/avsm/avsm_resolve_pass.h"
#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/capture/capture_sort_pass.h"
#include "passes/frame/hair_geometry.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/frame/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "support/gpu_test.h"
#include "support/test_volumes.h"

namespace avsm {
namespace avsm_shadow_test {  // one per file: test targets are unity builds
namespace {

// The GPU fixture (validation + synchronization validation; any message fails the
// test) under a suite name of its own, so --gtest_filter='Avsm*' selects these tests.
using AvsmShadowTest = testing::GpuTest;

using core::AvsmCurve;
using passes::AvsmMapLayout;

// Resolve and mips run the same core as the CPU reference; only float rounding
// (e.g. contracted multiply-adds in the device compiler) may differ.
constexpr float kCoreTolerance = 1e-5f;
// Float rounding in the core's interpolation (see the resolve test): a few ulps below 1.
constexpr float kMonotoneSlack = 1e-6f;

using shared::kListEnd;
// The depth range of the tests' lists; their maps store nodes over it.
constexpr float kNear = 1.0f, kFar = 100.0f;
// One 16-bit step of a stored node (shaders/shared/map_layouts.h): what a node may move
// by when stored (half a step) or between device and CPU (a step: rounding in the
// core can put a value on the other side of a rounding boundary).
constexpr float kDepthStep = (kFar - kNear) / 65535.0f, kTransStep = 1.0f / 65535.0f;
constexpr float kStoredDepthTolerance = kDepthStep + kCoreTolerance;
constexpr float kStoredTransTolerance = kTransStep + kCoreTolerance;

// ---- Capture lists built on the CPU ----

using Segment = shared::CaptureSegment;  // shaders/shared/capture.h

struct Lists {
  uint32_t resolution = 0;
  std::vector<uint32_t> heads;  // resolution^2, kListEnd for an empty list
  std::vector<Segment> nodes;

  // Texel `texel`'s segments in the order the resolve walks them: from the head along `next`.
  std::vector<Segment> walk(uint32_t texel) const {
    std::vector<Segment> out;
    for (uint32_t node = heads[texel]; node != kListEnd; node = nodes[node].next) out.push_back(nodes[node]);
    return out;
  }
};

// Appends every texel's segments in one random global interleaving, the way the
// captures' atomics do: each append takes the next index and points at the texel's
// previous head, so `next` always points at an older (smaller) index.
Lists make_lists(uint32_t resolution, const std::vector<std::vector<Segment>>& per_texel, std::mt19937& rng) {
  std::vector<std::pair<uint32_t, uint32_t>> appends;  // (texel, segment)
  for (uint32_t texel = 0; texel < per_texel.size(); ++texel)
    for (uint32_t s = 0; s < per_texel[texel].size(); ++s) appends.emplace_back(texel, s);
  std::shuffle(appends.begin(), appends.end(), rng);
  Lists lists;
  lists.resolution = resolution;
  lists.heads.assign(size_t(resolution) * resolution, kListEnd);
  for (const auto& [texel, s] : appends) {
    Segment segment = per_texel[texel][s];
    segment.next = lists.heads[texel];
    lists.heads[texel] = uint32_t(lists.nodes.size());
    lists.nodes.push_back(segment);
  }
  return lists;
}

// Overlapping segments anywhere in [kNear, kFar): some of zero length, some running
// past the far depth (the core clamps them), some opaque (exit_trans exactly 0).
std::vector<Segment> random_segments(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> entry(kNear, kFar), length(0.0f, 20.0f), trans(0.0f, 1.0f), u(0.0f, 1.0f);
  std::vector<Segment> out;
  for (int i = 0; i < count; ++i) {
    Segment s{};
    s.entry = entry(rng);
    const float kind = u(rng);
    s.exit_depth = s.entry + (kind < 0.15f ? 0.0f : length(rng));
    const float opacity = u(rng);
    s.exit_trans = opacity < 0.1f ? 0.0f : (opacity < 0.15f ? 1.0f : trans(rng));
    out.push_back(s);
  }
  return out;
}

std::vector<std::vector<Segment>> random_texel_segments(std::mt19937& rng, uint32_t resolution, int max_count) {
  std::uniform_int_distribution<int> count(0, max_count);
  std::vector<std::vector<Segment>> per_texel(size_t(resolution) * resolution);
  for (auto& segments : per_texel) segments = random_segments(rng, count(rng));
  return per_texel;
}

// ---- Stored curves (layout: shaders/shared/map_layouts.h, passes/shadows/techniques/avsm_map_layout.h) ----

// A texel's N stored nodes (decoded), padding included.
struct StoredCurve {
  std::vector<float> depth, trans;
};

// What avsm_map_store writes for curve c over [near_depth, far_depth], decoded: its nodes
// packed to 16-bit depth and transmittance, the last one repeated into unused slots.
StoredCurve stored_form(const AvsmCurve& c, int n, float near_depth = kNear, float far_depth = kFar) {
  StoredCurve s;
  for (int i = 0; i < n; ++i) {
    const int k = std::min(i, c.count - 1);
    const uint32_t node = shared::avsm_node_pack(c.depth[k], c.trans[k], near_depth, far_depth);
    s.depth.push_back(shared::avsm_node_depth(node, near_depth, far_depth));
    s.trans.push_back(shared::avsm_node_transmittance(node));
  }
  return s;
}

// A depth as a stored node holds it over [kNear, kFar].
float stored_depth(float d) {
  return shared::avsm_node_depth(shared::avsm_node_pack(d, 1.0f, kNear, kFar), kNear, kFar);
}

StoredCurve read_texel(const std::vector<glm::vec4>& map, const AvsmMapLayout& layout, uint32_t level, uint32_t x,
                       uint32_t y, float near_depth = kNear, float far_depth = kFar) {
  const uint64_t base = layout.texel_base(level, x, y);
  EXPECT_LE(base + layout.vec4s_per_texel(), map.size());
  StoredCurve s;
  for (uint32_t i = 0; i < layout.nodes; ++i) {
    const AvsmMapLayout::Node node = AvsmMapLayout::node(map.data() + base, i, near_depth, far_depth);
    s.depth.push_back(node.depth);
    s.trans.push_back(node.transmittance);
  }
  return s;
}

// A stored curve loaded back with all N slots as nodes, as avsm_mips.comp's load_curve does.
AvsmCurve as_curve(const StoredCurve& s) {
  AvsmCurve c = core::avsm_clear(0.0f);
  for (size_t i = 0; i < s.depth.size(); ++i) {
    c.depth[i] = s.depth[i];
    c.trans[i] = s.trans[i];
  }
  c.count = int(s.depth.size());
  return c;
}

AvsmCurve cpu_resolve(const std::vector<Segment>& list, float far_depth, int n) {
  AvsmCurve c = core::avsm_clear(far_depth);
  for (const Segment& s : list) core::avsm_insert_segment(c, s.entry, s.exit_depth, s.exit_trans, n);
  return c;
}

// Front to back by (entry, exit, transmittance), as CaptureSortPass orders a list.
std::vector<Segment> sorted_list(std::vector<Segment> list) {
  std::stable_sort(list.begin(), list.end(), [](const Segment& a, const Segment& b) {
    if (a.entry != b.entry) return a.entry < b.entry;
    if (a.exit_depth != b.exit_depth) return a.exit_depth < b.exit_depth;
    return a.exit_trans < b.exit_trans;
  });
  return list;
}

// The CPU reference of a whole map stored over [near_depth, far_depth]: level 0 from the
// lists (sorted first if `sort`), every other level from the CPU level above (2x2
// children, clamped at odd edges) through avsm_mip_merge.
std::vector<std::vector<StoredCurve>> cpu_map(const Lists& lists, const AvsmMapLayout& layout, float near_depth,
                                              float far_depth, bool sort = false) {
  const int n = int(layout.nodes);
  std::vector<std::vector<StoredCurve>> levels(layout.levels);
  for (uint32_t texel = 0; texel < lists.heads.size(); ++texel) {
    const std::vector<Segment> list = sort ? sorted_list(lists.walk(texel)) : lists.walk(texel);
    levels[0].push_back(stored_form(cpu_resolve(list, far_depth, n), n, near_depth, far_depth));
  }
  for (uint32_t level = 1; level < layout.levels; ++level) {
    const uint32_t size = layout.level_size(level), above = layout.level_size(level - 1);
    auto child = [&](uint32_t x, uint32_t y) {
      return as_curve(levels[level - 1][size_t(std::min(y, above - 1)) * above + std::min(x, above - 1)]);
    };
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x)
        levels[level].push_back(stored_form(core::avsm_mip_merge(child(2 * x, 2 * y), child(2 * x + 1, 2 * y),
                                                                 child(2 * x, 2 * y + 1), child(2 * x + 1, 2 * y + 1), n),
                                            n, near_depth, far_depth));
  }
  return levels;
}

std::string describe(const StoredCurve& s) {
  std::ostringstream out;
  for (size_t i = 0; i < s.depth.size(); ++i) out << " (" << s.depth[i] << ", " << s.trans[i] << ")";
  return out.str();
}

bool bit_identical(const StoredCurve& a, const StoredCurve& b) {
  return std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0 &&
         std::memcmp(a.trans.data(), b.trans.data(), a.trans.size() * sizeof(float)) == 0;
}

// ---- Running resolve (and mips) alone in a graph ----

// The state upload_image / upload_buffer leave a resource in: everything before finished and is visible.
rg::ImportState uploaded(VkImageLayout layout) {
  return {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT, layout};
}

// Imports the lists (heads as an R32_UINT storage image, nodes as a buffer) and a map
// buffer, runs, over [kNear, kFar], [CaptureSortPass,] AvsmResolvePass and (when layout.levels > 1)
// AvsmMipsPass on the device, reads the whole map back.
std::vector<glm::vec4> run_resolve(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const Lists& lists,
                                   const AvsmMapLayout& layout, bool sort = false) {
  const uint32_t res = lists.resolution;
  gpu::ImageDesc desc;
  desc.width = desc.height = res;
  desc.format = passes::kCaptureHeadFormat;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "test list heads";
  gpu::Image heads = gpu::Image::create(ctx, desc);
  gpu::upload_image(ctx, heads, lists.heads.data(), lists.heads.size() * sizeof(uint32_t), VK_IMAGE_LAYOUT_GENERAL);
  gpu::Buffer nodes = gpu::create_buffer_from(ctx, lists.nodes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "test list nodes");
  gpu::Buffer map = gpu::Buffer::create(ctx, {layout.bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                              gpu::MemoryLocation::DeviceLocal, "test avsm map"});

  rg::Graph graph;
  passes::CaptureLists imported;
  imported.heads = graph.import_texture("list heads", {res, res, 1, 1, 1, passes::kCaptureHeadFormat},
                                        uploaded(VK_IMAGE_LAYOUT_GENERAL), rg::ImportState::none());
  imported.nodes = graph.import_buffer("list nodes", {nodes.size()}, uploaded(VK_IMAGE_LAYOUT_UNDEFINED),
                                       rg::ImportState::none());
  rg::BufferHandle map_handle =
      graph.import_buffer("avsm map", {map.size()}, rg::ImportState::none(), rg::ImportState::of(rg::Usage::TransferSrc));
  const passes::CaptureSortPass sort_pass(ctx, shaders);
  const passes::AvsmResolvePass resolve(ctx, shaders);
  const passes::AvsmMipsPass mips(ctx, shaders);
  passes::CaptureLists lists_to_resolve = imported;
  if (sort) lists_to_resolve = sort_pass.add_to_graph(graph, "test", imported, res);
  rg::BufferHandle written = resolve.add_to_graph(graph, "test", lists_to_resolve, map_handle, layout, kNear, kFar);
  mips.add_to_graph(graph, "test", written, layout, kNear, kFar);

  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  executor.bind(imported.heads, heads);
  executor.bind(imported.nodes, nodes);
  executor.bind(map_handle, map);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
  return gpu::read_buffer<glm::vec4>(ctx, map);
}

// Compares every stored node of every level with the CPU map; returns the largest error,
// in tolerances (kStoredDepthTolerance, kStoredTransTolerance).
float compare_map(const std::vector<glm::vec4>& gpu_map, const std::vector<std::vector<StoredCurve>>& cpu,
                  const AvsmMapLayout& layout, const std::string& what) {
  float max_error = 0.0f;
  int reported = 0;
  size_t bad_texels = 0;
  for (uint32_t level = 0; level < layout.levels; ++level) {
    const uint32_t size = layout.level_size(level);
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const StoredCurve got = read_texel(gpu_map, layout, level, x, y);
        const StoredCurve& want = cpu[level][size_t(y) * size + x];
        // In 16-bit steps: depth and transmittance on one scale.
        float texel_error = 0.0f;
        for (uint32_t i = 0; i < layout.nodes; ++i) {
          texel_error = std::max(texel_error, std::abs(got.depth[i] - want.depth[i]) / kStoredDepthTolerance);
          texel_error = std::max(texel_error, std::abs(got.trans[i] - want.trans[i]) / kStoredTransTolerance);
        }
        max_error = std::max(max_error, texel_error);
        if (!(texel_error <= 1.0f)) {
          ++bad_texels;
          if (reported++ < 3)
            ADD_FAILURE() << what << ", level " << level << ", texel (" << x << ", " << y << "): |error| "
                          << texel_error << " tolerances"
                          << "\n  GPU:" << describe(got) << "\n  CPU:" << describe(want);
        }
      }
  }
  EXPECT_EQ(bad_texels, size_t(0)) << what << ": texels differing from the CPU reference by more than a 16-bit step";
  return max_error;
}

// ---- 1. Resolve matches the C++ core ----

TEST_F(AvsmShadowTest, AvsmResolveMatchesCpuReference) {
  constexpr uint32_t kRes = 16;
  std::mt19937 rng(2024);
  for (uint32_t n : {4u, 8u, 12u, 16u}) {
    const Lists lists = make_lists(kRes, random_texel_segments(rng, kRes, 40), rng);
    const AvsmMapLayout layout{kRes, n, 1};
    const std::vector<glm::vec4> gpu_map = run_resolve(ctx(), shaders(), lists, layout);
    ASSERT_EQ(gpu_map.size(), layout.bytes() / 16);
    const auto cpu = cpu_map(lists, layout, kNear, kFar);
    const std::string what = "N = " + std::to_string(n);
    const float max_error = compare_map(gpu_map, cpu, layout, what);
    std::cout << "[ resolve N=" << n << " ] " << lists.nodes.size() << " segments, max |GPU - CPU| " << max_error
              << "\n";

    size_t compressed = 0;
    float max_rise = 0.0f;
    for (uint32_t texel = 0; texel < kRes * kRes; ++texel) {
      const uint32_t x = texel % kRes, y = texel / kRes;
      const AvsmCurve reference = cpu_resolve(lists.walk(texel), kFar, int(n));
      const StoredCurve got = read_texel(gpu_map, layout, 0, x, y);
      const std::string where = what + ", texel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
      ASSERT_LE(reference.count, int(n)) << where;
      compressed += lists.walk(texel).size() * 2 + 1 > n;
      // Nothing is in front of the first node: it is fully lit.
      EXPECT_EQ(got.trans[0], 1.0f) << where << ":" << describe(got);
      // The last node (behind every segment) is never removed; stored, it moves by at most half a step.
      EXPECT_NEAR(got.depth[n - 1], reference.depth[reference.count - 1], kStoredDepthTolerance) << where;
      EXPECT_NEAR(got.trans[n - 1], reference.trans[reference.count - 1], kStoredTransTolerance) << where;
      // Depths never decrease (the 16-bit depths keep the order); transmittance never
      // increases, up to float rounding in the core's linear interpolation (the CPU core
      // does the same; measured: at most 6e-8), which storing can turn into one step.
      for (uint32_t i = 1; i < n; ++i) {
        EXPECT_GE(got.depth[i], got.depth[i - 1]) << where << " node " << i << ":" << describe(got);
        EXPECT_LE(got.trans[i], got.trans[i - 1] + kTransStep + kMonotoneSlack)
            << where << " node " << i << ":" << describe(got);
        max_rise = std::max(max_rise, got.trans[i] - got.trans[i - 1]);
      }
      if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(compressed, size_t(kRes * kRes / 2)) << what << ": most lists should need compression";
    std::cout << "[ resolve N=" << n << " ] " << compressed << " of " << kRes * kRes
              << " lists compressed, largest rise of transmittance along a curve " << max_rise << "\n";
  }
}

// ---- 2. Enough nodes reproduce the exact curve ----

TEST_F(AvsmShadowTest, AvsmResolveWithEnoughNodesIsExact) {
  constexpr uint32_t kRes = 16;
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> depth(kNear, 0.95f * kFar), trans(0.0f, 1.0f), u(0.0f, 1.0f);
  for (uint32_t n : {4u, 8u, 12u, 16u}) {
    // At most N/2 - 1 disjoint segments: 1 + 2k <= N - 1 nodes, nothing is ever removed.
    // Their ends lie on the stored depths, so storing moves only transmittances (by at
    // most half a step).
    std::uniform_int_distribution<int> count(0, int(n / 2) - 1);
    std::vector<std::vector<Segment>> per_texel(kRes * kRes);
    for (auto& segments : per_texel) {
      const int k = count(rng);
      std::vector<float> ends;
      for (int i = 0; i < 2 * k; ++i) ends.push_back(stored_depth(depth(rng)));
      std::sort(ends.begin(), ends.end());
      for (int i = 0; i < k; ++i)
        segments.push_back({ends[2 * i], ends[2 * i + 1], u(rng) < 0.1f ? 0.0f : trans(rng), 0});
      std::shuffle(segments.begin(), segments.end(), rng);  // any arrival order
    }
    const Lists lists = make_lists(kRes, per_texel, rng);
    const AvsmMapLayout layout{kRes, n, 1};
    const std::vector<glm::vec4> gpu_map = run_resolve(ctx(), shaders(), lists, layout);

    float max_error = 0.0f;
    for (uint32_t texel = 0; texel < kRes * kRes; ++texel) {
      const uint32_t x = texel % kRes, y = texel / kRes;
      const AvsmCurve stored = as_curve(read_texel(gpu_map, layout, 0, x, y));
      const std::vector<Segment> list = lists.walk(texel);
      for (float d = 0.0f; d < 1.1f * kFar; d += 0.0917f) {
        float exact = 1.0f;
        for (const Segment& s : list) exact *= core::avsm_segment_transmittance(s.entry, s.exit_depth, s.exit_trans, d);
        const float error = std::abs(core::avsm_evaluate_linear(stored, d) - exact);
        max_error = std::max(max_error, error);
        ASSERT_LE(error, kStoredTransTolerance) << "N = " << n << ", texel (" << x << ", " << y << ") at depth " << d
                                         << ": stored" << describe(read_texel(gpu_map, layout, 0, x, y));
      }
    }
    std::cout << "[ exact N=" << n << "   ] max |stored curve - product of segments| " << max_error << "\n";
  }
}

// ---- 3. Mips match the CPU chain ----

TEST_F(AvsmShadowTest, AvsmMipsMatchCpuReference) {
  std::mt19937 rng(7);
  for (uint32_t res : {16u, 12u}) {  // 12 -> 6 -> 3 -> 1: the 3 -> 1 step clamps at the odd edge
    for (uint32_t n : {4u, 8u, 12u, 16u}) {
      const Lists lists = make_lists(res, random_texel_segments(rng, res, 24), rng);
      const AvsmMapLayout layout{res, n, AvsmMapLayout::full_mip_count(res)};
      ASSERT_EQ(layout.level_size(layout.levels - 1), 1u);
      const std::vector<glm::vec4> gpu_map = run_resolve(ctx(), shaders(), lists, layout);
      const auto cpu = cpu_map(lists, layout, kNear, kFar);
      const std::string what = std::to_string(res) + "^2, N = " + std::to_string(n);
      const float max_error = compare_map(gpu_map, cpu, layout, what);
      std::cout << "[ mips " << what << " ] " << layout.levels << " levels, max |GPU - CPU| " << max_error << "\n";
      // The coarsest texel averages everything: not the cleared curve.
      const StoredCurve top = read_texel(gpu_map, layout, layout.levels - 1, 0, 0);
      EXPECT_LT(top.trans[n - 1], 0.9f) << what << ":" << describe(top);
      if (::testing::Test::HasFailure()) return;
    }
  }
}

// ---- 4a. Sorting makes the resolve independent of the append order ----

// The same segments per texel appended in two different global orders (as two runs of
// the captures' atomics might): unsorted, the compressed maps differ; sorted, they are
// the same bit for bit and match the CPU core over the sorted lists. Lists of 0..40
// segments take both of the sort's paths (in registers up to 32, in memory beyond).
TEST_F(AvsmShadowTest, AvsmSortedResolveIgnoresAppendOrder) {
  constexpr uint32_t kRes = 16;
  std::mt19937 rng(5);
  const std::vector<std::vector<Segment>> per_texel = random_texel_segments(rng, kRes, 40);
  const Lists first = make_lists(kRes, per_texel, rng);
  const Lists second = make_lists(kRes, per_texel, rng);
  size_t long_lists = 0;
  for (const auto& segments : per_texel) long_lists += segments.size() > 32;
  ASSERT_GT(long_lists, 0u);
  for (uint32_t n : {4u, 8u, 16u}) {
    const AvsmMapLayout layout{kRes, n, 1};
    const size_t bytes = layout.bytes();
    const std::vector<glm::vec4> unsorted_first = run_resolve(ctx(), shaders(), first, layout);
    const std::vector<glm::vec4> unsorted_second = run_resolve(ctx(), shaders(), second, layout);
    ASSERT_NE(std::memcmp(unsorted_first.data(), unsorted_second.data(), bytes), 0)
        << "N = " << n << ": the append order should matter without the sort";
    const std::vector<glm::vec4> sorted_first = run_resolve(ctx(), shaders(), first, layout, /*sort=*/true);
    const std::vector<glm::vec4> sorted_second = run_resolve(ctx(), shaders(), second, layout, /*sort=*/true);
    EXPECT_EQ(std::memcmp(sorted_first.data(), sorted_second.data(), bytes), 0)
        << "N = " << n << ": sorted resolves of the same segments differ";
    const float max_error = compare_map(sorted_first, cpu_map(first, layout, kNear, kFar, /*sort=*/true), layout,
                                        "sorted, N = " + std::to_string(n));
    std::cout << "[ sort N=" << n << "    ] " << long_lists << " lists longer than 32, max |GPU - CPU sorted| "
              << max_error << "\n";
  }
}

// Long lists next to short ones in one subgroup (a row of 8 texels), as hair gives them:
// each sorts completely, so the resolve matches the CPU core over the sorted lists. The
// sort used to stop part way once its lanes' loops had iterated 65535 times together
// (lavapipe's limit; shaders/passes/shadows/capture/capture_sort.comp): 12,000 segments would have taken
// it 72 million steps. A list over its 16,384-segment limit stays whole in capture order.
TEST_F(AvsmShadowTest, AvsmSortSortsLongListsCompletely) {
  constexpr uint32_t kRes = 8, kNodes = 16;
  constexpr size_t kMaxSortedSegments = 16384;  // capture_sort.comp
  std::mt19937 rng(17);
  std::vector<std::vector<Segment>> per_texel = random_texel_segments(rng, kRes, 40);
  const int lengths[kRes] = {1, 12000, 2, 700, 20000, 3000, 33, 1};
  for (uint32_t x = 0; x < kRes; ++x) per_texel[x] = random_segments(rng, lengths[x]);
  const Lists lists = make_lists(kRes, per_texel, rng);
  const AvsmMapLayout layout{kRes, kNodes, 1};
  const std::vector<glm::vec4> map = run_resolve(ctx(), shaders(), lists, layout, /*sort=*/true);
  std::vector<std::vector<StoredCurve>> cpu(1);
  size_t order_matters = 0;
  for (uint32_t texel = 0; texel < kRes * kRes; ++texel) {
    const std::vector<Segment> list = lists.walk(texel);
    const StoredCurve unsorted = stored_form(cpu_resolve(list, kFar, kNodes), kNodes);
    const StoredCurve sorted = stored_form(cpu_resolve(sorted_list(list), kFar, kNodes), kNodes);
    cpu[0].push_back(list.size() > kMaxSortedSegments ? unsorted : sorted);
    order_matters += !bit_identical(unsorted, sorted);
  }
  const float max_error = compare_map(map, cpu, layout, "long lists, sorted, N = 16");
  std::cout << "[ sort long   ] lists of up to 20000 segments, max |GPU - CPU| " << max_error << "\n";
  // Not vacuous: the long lists' curves depend on their order.
  EXPECT_GE(order_matters, 4u);
}

// ---- Rendering scenes ----

scene::Scene default_scene(int nodes, int resolution) {
  scene::Scene scene = scene::load_scene(AVSM_DEFAULT_SCENE);
  // Dense maps of that resolution (the default scene's are paged), as --shadow-res gives.
  for (scene::Light& light : scene.lights)
    passes::apply_shadow_overrides({.technique = "avsm", .nodes = nodes, .resolution = resolution, .sort = true}, light);
  return scene;
}

constexpr uint32_t kFrameWidth = 64, kFrameHeight = 36;

// One frame: declare, record, submit, wait, read the capture counters.
void render_frame(gpu::Context& ctx, renderer::SceneRenderer& renderer, rg::vulkan::Executor& executor,
                  const passes::View& view) {
  rg::Graph graph = renderer.build_frame(view);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
  renderer.finish_frame();
}

std::vector<std::vector<uint8_t>> read_maps(gpu::Context& ctx, const passes::ShadowMaps& shadows) {
  std::vector<std::vector<uint8_t>> maps;
  for (uint32_t light = 0; light < shadows.light_count(); ++light)
    maps.push_back(gpu::read_buffer_bytes(ctx, shadows.avsm_map(light)));
  return maps;
}

// Texels of a map (every level) whose stored nodes are not a curve: depths out of the
// light's depth range or out of order, transmittance rising (by more than a step).
size_t invalid_stored_curves(const std::vector<uint8_t>& bytes, const AvsmMapLayout& layout,
                             const passes::LightView& view) {
  std::vector<glm::vec4> texels(bytes.size() / sizeof(glm::vec4));
  std::memcpy(texels.data(), bytes.data(), texels.size() * sizeof(glm::vec4));
  size_t invalid = 0;
  for (uint32_t level = 0; level < layout.levels; ++level)
    for (uint32_t y = 0; y < layout.level_size(level); ++y)
      for (uint32_t x = 0; x < layout.level_size(level); ++x) {
        const StoredCurve c = read_texel(texels, layout, level, x, y, view.near_depth, view.far_depth);
        bool ok = c.depth.front() >= view.near_depth && c.depth.back() <= view.far_depth * (1.0f + 1e-6f);
        for (size_t i = 1; i < c.depth.size(); ++i)
          ok = ok && c.depth[i] >= c.depth[i - 1] && c.trans[i] <= c.trans[i - 1] + kTransStep + kMonotoneSlack;
        invalid += !ok;
      }
  return invalid;
}

// ---- 4b. A sorted resolve of a whole scene is the same bit for bit ----

TEST_F(AvsmShadowTest, AvsmSortedResolveIsBitIdenticalAcrossRuns) {
  const scene::Scene scene = default_scene(8, 64);
  ASSERT_GE(scene.lights.size(), 2u);
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  std::vector<std::vector<std::vector<uint8_t>>> runs;
  for (int run = 0; run < 2; ++run) {
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    // The first frame may overflow the first guess of the capture size (then which
    // segments were dropped depends on the order of the atomics); the second has room.
    render_frame(ctx(), renderer, executor, view);
    render_frame(ctx(), renderer, executor, view);
    for (const passes::LightShadowStats& stats : renderer.shadows().frame_stats())
      ASSERT_FALSE(stats.overflowed) << stats.light << ": the comparison needs every segment captured";
    runs.push_back(read_maps(ctx(), renderer.shadows()));
  }
  ASSERT_EQ(runs[0].size(), scene.lights.size());
  for (size_t light = 0; light < runs[0].size(); ++light) {
    const std::vector<uint8_t>& a = runs[0][light];
    const std::vector<uint8_t>& b = runs[1][light];
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GT(a.size(), 0u);
    // Not vacuous: the light's map holds shadow (some node well below 1).
    std::vector<glm::vec4> texels(a.size() / sizeof(glm::vec4));
    std::memcpy(texels.data(), a.data(), texels.size() * sizeof(glm::vec4));
    const AvsmMapLayout level0{64, 8, 1};
    size_t shadowed = 0;  // transmittances decode alike over any depth range: the tests' will do
    for (uint32_t y = 0; y < 64; ++y)
      for (uint32_t x = 0; x < 64; ++x) shadowed += read_texel(texels, level0, 0, x, y).trans.back() < 0.5f;
    EXPECT_GT(shadowed, 0u) << scene.lights[light].name << ": no texel of level 0 is shadowed";
    size_t differing = 0;
    for (size_t i = 0; i < a.size(); ++i) differing += a[i] != b[i];
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size()), 0)
        << scene.lights[light].name << ": " << differing << " of " << a.size() << " map bytes differ between runs";
    std::cout << "[ sorted      ] " << scene.lights[light].name << ": " << a.size() << " map bytes, " << shadowed
              << " level-0 texels below 0.5, " << differing << " bytes differ\n";
  }
}

// ---- 4c. The default scene's maps against the C++ core, every texel ----

// Light `light`'s capture lists as the renderer kept them for the lookups
// (ShadowOptions::keep_reference), read back.
Lists read_looked_up_lists(gpu::Context& ctx, const passes::ShadowMaps& shadows, uint32_t light) {
  Lists lists;
  lists.resolution = shadows.map_layout(light).resolution;
  lists.heads = gpu::read_buffer<uint32_t>(ctx, shadows.looked_up_list_heads(light));
  lists.nodes = gpu::read_buffer<Segment>(ctx, shadows.looked_up_list_nodes(light));
  return lists;
}

bool same_segments(const std::vector<Segment>& a, const std::vector<Segment>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const Segment& x, const Segment& y) {
           return x.entry == y.entry && x.exit_depth == y.exit_depth && x.exit_trans == y.exit_trans;
         });
}

// Both default lights at 32^2, AVSM-16, sorted lists: the sun's map holds the hair
// curtain's longest lists (over a thousand segments), the spot's has mips. Every list
// must come out of the sort front to back, and every stored node of every level must be
// the C++ core's over the sorted lists, bit for bit. (The sort used to stop part way on
// long lists under lavapipe's loop limit: shaders/passes/shadows/capture/capture_sort.comp.)
TEST_F(AvsmShadowTest, AvsmDefaultSceneMatchesTheCoreAtEveryTexel) {
  constexpr uint32_t kNodes = 16, kResolution = 32;
  const scene::Scene scene = default_scene(int(kNodes), int(kResolution));
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, {.keep_reference = true});
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  // The second frame's capture has room for every segment (see 4b).
  render_frame(ctx(), renderer, executor, view);
  render_frame(ctx(), renderer, executor, view);
  const passes::ShadowMaps& shadows = renderer.shadows();
  ASSERT_EQ(shadows.light_count(), 2u);
  for (uint32_t light = 0; light < shadows.light_count(); ++light) {
    const std::string name = scene.lights[light].name;
    ASSERT_FALSE(shadows.frame_stats().at(light).overflowed) << name;
    const passes::LightView& light_view = shadows.light_views().at(light);
    const AvsmMapLayout& layout = shadows.map_layout(light);
    ASSERT_EQ(layout.nodes, kNodes) << name;
    ASSERT_EQ(layout.resolution, kResolution) << name;
    const Lists lists = read_looked_up_lists(ctx(), shadows, light);
    size_t longest = 0, compressed = 0, unsorted = 0;
    for (uint32_t texel = 0; texel < lists.heads.size(); ++texel) {
      const std::vector<Segment> list = lists.walk(texel);
      longest = std::max(longest, list.size());
      compressed += 2 * list.size() + 1 > kNodes;
      if (!same_segments(list, sorted_list(list)) && unsorted++ < 3)
        ADD_FAILURE() << name << ", texel (" << texel % kResolution << ", " << texel / kResolution << "): "
                      << list.size() << " segments not sorted front to back";
    }
    EXPECT_EQ(unsorted, 0u) << name << ": lists the sort left out of order";

    const std::vector<glm::vec4> map = gpu::read_buffer<glm::vec4>(ctx(), shadows.avsm_map(light));
    const auto cpu = cpu_map(lists, layout, light_view.near_depth, light_view.far_depth, /*sort=*/true);
    size_t differing = 0;
    for (uint32_t level = 0; level < layout.levels; ++level) {
      const uint32_t size = layout.level_size(level);
      for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
          const StoredCurve got = read_texel(map, layout, level, x, y, light_view.near_depth, light_view.far_depth);
          const StoredCurve& want = cpu[level][size_t(y) * size + x];
          if (bit_identical(got, want)) continue;
          if (differing++ < 3)
            ADD_FAILURE() << name << ", level " << level << ", texel (" << x << ", " << y << ")"
                          << "\n  GPU:" << describe(got) << "\n  CPU:" << describe(want);
        }
    }
    EXPECT_EQ(differing, 0u) << name << ": texels whose stored curve is not the C++ core's";
    std::cout << "[ default 16  ] " << name << ": " << layout.levels << " levels, " << compressed << " of "
              << lists.heads.size() << " lists compressed, longest " << longest << " segments; " << unsorted
              << " unsorted, " << differing << " texels differ from the core\n";
    // Not vacuous: lists that need compressing, the sun's longer than the sort's
    // register-sized lists used to be (32) by far.
    EXPECT_GT(compressed, 20u) << name;
    if (light == 0) {
      EXPECT_GT(longest, 1000u) << name << ": the sun's map should hold the hair's longest lists";
    }
  }
}

// ---- 5. The uncompressed lookup against Beer-Lambert through a constant box ----

using testing::load_box_volume;

// 32^3 voxels of density 1, voxel 0.1: voxel centres span [0, 3.1] per axis; the
// trilinear density is 1 there and ramps to 0 over one voxel on each side.
constexpr int kBoxVoxels = 32;
constexpr float kBoxVoxelSize = 0.1f;
constexpr float kBoxLow = 0.0f, kBoxHigh = (kBoxVoxels - 1) * kBoxVoxelSize;

// Integral of the box's trilinear density along +y from height y to infinity
// (x and z inside the full-density core): a trapezoid profile, in closed form.
double density_path_above(double y) {
  const double v = kBoxVoxelSize, lo = kBoxLow, hi = kBoxHigh;
  if (y >= hi + v) return 0.0;
  if (y >= hi) return (hi + v - y) * (hi + v - y) / (2.0 * v);                       // inside the top ramp
  if (y >= lo) return 0.5 * v + (hi - y);                                              // inside the core
  if (y >= lo - v) return 0.5 * v + (hi - lo) + 0.5 * v - (y - lo + v) * (y - lo + v) / (2.0 * v);  // bottom ramp
  return v + (hi - lo);                                                                // below: the whole box
}

// One way of looking shadows up, and how far from exp(-sigma L) it may be.
struct BoxSetup {
  const char* name;
  const char* technique;
  scene::ShadowFilter filter;
  int nodes;
  float tolerance;
  std::map<std::string, double> parameters = {};
};

// A 32^3 box of density 1 lit straight down by one sun per setup (at most 4); probes
// on a vertical line through its centre (above: lit, inside, below: through all of
// it) compared with the closed-form Beer-Lambert transmittance.
void expect_box_probes_match_beer_lambert(gpu::Context& ctx, const gpu::ShaderLibrary& shaders,
                                          const std::vector<BoxSetup>& setups) {
  constexpr float kSigma = 0.5f;  // extinction per unit density per world unit: T through the box = exp(-1.6)
  scene::VolumeOptions options;
  options.extinction_scale = kSigma;
  scene::Scene scene;
  scene.file = "constant box scene (built in the test)";
  scene.volumes.push_back(
      load_box_volume({{glm::ivec3(0), glm::ivec3(kBoxVoxels - 1), 1.0f}}, kBoxVoxelSize, options));
  scene.volumes.back().name = "box";
  scene.bounds.extend(scene.volumes.back().world_bounds);
  const glm::vec3 centre = scene.bounds.center();
  for (const BoxSetup& setup : setups) {
    scene::Light sun;
    sun.name = setup.name;
    sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    sun.shadow.technique = setup.technique;
    sun.shadow.filter = setup.filter;
    sun.shadow.nodes = setup.nodes;
    sun.shadow.resolution = 64;
    sun.shadow.parameters = setup.parameters;
    scene.lights.push_back(sun);
  }
  scene::Camera camera;
  camera.position = centre + glm::vec3(0.0f, 1.0f, 8.0f);
  camera.target = centre;
  scene.cameras.push_back(camera);

  // The light box spans the bounding sphere: y from centre - r to centre + r, r = 2.86.
  std::vector<glm::vec3> probes;
  std::vector<float> expected;
  for (float y = 4.3f; y > -1.25f; y -= 0.137f) {
    probes.emplace_back(centre.x, y, centre.z);
    expected.push_back(float(std::exp(-double(kSigma) * density_path_above(y))));
  }
  renderer::SceneRenderer renderer(ctx, shaders, scene, kFrameWidth, kFrameHeight);
  renderer.set_probes(probes);
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  // Two frames: maps fitted to the view fill their texels with the box, and the first
  // frame's capture grows to hold it.
  for (int frame = 0; frame < 2; ++frame)
    render_frame(ctx, renderer, executor, passes::make_view(camera, kFrameWidth, kFrameHeight));
  for (const passes::LightShadowStats& stats : renderer.shadows().frame_stats()) {
    ASSERT_FALSE(stats.lost_shadowing()) << stats.light;
  }
  const std::vector<std::vector<float>> results = renderer.probe_results();
  ASSERT_EQ(results.size(), setups.size());
  for (size_t light = 0; light < setups.size(); ++light) {
    float max_error = 0.0f;
    for (size_t i = 0; i < probes.size(); ++i) {
      const float got = results[light][i];
      max_error = std::max(max_error, std::abs(got - expected[i]));
      EXPECT_NEAR(got, expected[i], setups[light].tolerance) << setups[light].name << " at y = " << probes[i].y;
    }
    std::cout << "[ box probes  ] " << setups[light].name << ": max |probe - exp(-sigma L)| " << max_error << " over "
              << probes.size() << " probes (tolerance " << setups[light].tolerance << ")\n";
  }
  // The line really crosses the box: fully lit above it, exp(-sigma 3.2) below it.
  EXPECT_EQ(expected.front(), 1.0f);
  EXPECT_NEAR(expected.back(), std::exp(-kSigma * kBoxVoxels * kBoxVoxelSize), 1e-6f);
}

// Uncompressed: the capture integrates the trilinear density with the midpoint rule
// at a quarter voxel (restarting at brick boundaries, so the steps straddle the ramps
// at the box faces: O(step^2) kinks), and the list lookup interpolates transmittance
// linearly inside each 16-sample (0.4 unit) segment where the truth is exponential:
// up to T * tau^2 / 8 = 0.005 with tau = 0.2 per segment. 2e-2 covers both with room.
// AVSM with 16 nodes: the 8 segments through the box fit but the duplicated
// entry/exit depths are merged by compression; 0.05 allows for it.
TEST_F(AvsmShadowTest, AvsmUncompressedLookupMatchesBeerLambertThroughABox) {
  expect_box_probes_match_beer_lambert(ctx(), shaders(), {
      {"uncompressed point", "uncompressed", scene::ShadowFilter::point, 8, 2e-2f},
      {"uncompressed bilinear", "uncompressed", scene::ShadowFilter::bilinear, 8, 2e-2f},
      {"avsm16 point", "avsm", scene::ShadowFilter::point, 16, 5e-2f},
      {"avsm16 bilinear", "avsm", scene::ShadowFilter::bilinear, 16, 5e-2f},
  });
}

// The comparison techniques on the same box, each within its own expected error:
// - dsm: the capture's error (2e-2, as above) plus the compression threshold.
// - osm, 32 planes over the light's 5.7-unit depth range (0.18 per slice): receivers
//   look up one slice in front of themselves (the default depth bias), which under-
//   counts up to sigma * 0.18 = 0.09 of optical depth: T off by up to 1 - e^-0.09 = 0.086,
//   plus the capture's 0.02.
// - fom, 16 terms: looked up one slice (1/16 of the range, 0.36 units) early, which
//   under-counts up to sigma * 0.36 = 0.18 of optical depth (T off by up to 0.165),
//   and the windowed series smooths the box's edges over about that width: 0.2.
TEST_F(AvsmShadowTest, AvsmComparisonTechniquesMatchBeerLambertThroughABox) {
  expect_box_probes_match_beer_lambert(ctx(), shaders(), {
      {"dsm error 0.01", "dsm", scene::ShadowFilter::bilinear, 8, 3e-2f, {{"error", 0.01}}},
      {"dsm error 0.05", "dsm", scene::ShadowFilter::bilinear, 8, 7e-2f, {{"error", 0.05}}},
      {"osm 32", "osm", scene::ShadowFilter::bilinear, 8, 0.11f, {{"slices", 32}}},
      {"fom 16", "fom", scene::ShadowFilter::bilinear, 8, 0.2f, {{"terms", 16}}},
  });
}

// The constant debug technique (passes/shadows/techniques/constant/): no map, and every lookup
// inside the light's map returns its transmittance parameter, whatever casts there.
TEST_F(AvsmShadowTest, ConstantTechniqueReturnsItsTransmittanceEverywhere) {
  scene::Scene scene = default_scene(8, 64);
  scene.lights.resize(1);  // the sun: its map covers the whole scene
  scene.lights[0].shadow.technique = "constant";
  scene.lights[0].shadow.parameters["transmittance"] = 0.25;
  const glm::vec3 centre = scene.bounds.center(), extent = scene.bounds.max - scene.bounds.min;
  std::vector<glm::vec3> probes;
  for (float f : {-0.25f, 0.0f, 0.25f}) probes.push_back(centre + f * extent);
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
  renderer.set_probes(probes);
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  render_frame(ctx(), renderer, executor, passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight));
  EXPECT_FALSE(renderer.shadows().avsm_map(0));  // it keeps no map
  EXPECT_EQ(renderer.shadows().frame_stats().at(0).map_bytes, 0u);
  const std::vector<std::vector<float>> results = renderer.probe_results();
  ASSERT_EQ(results.size(), 1u);
  for (size_t i = 0; i < probes.size(); ++i) EXPECT_EQ(results[0][i], 0.25f) << "probe " << i;
}

// ---- 6. Capture overflow ----

bool all_finite(const gpu::ImageRGBA32F& image) {
  return std::all_of(image.pixels.begin(), image.pixels.end(), [](float v) { return std::isfinite(v); });
}

TEST_F(AvsmShadowTest, AvsmCaptureOverflowIsReportedClampedAndGrown) {
  const scene::Scene scene = default_scene(8, 64);
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  constexpr uint64_t kTinySegments = 64;
  {
    passes::ShadowOptions tiny;
    tiny.capture_limit_bytes = kTinySegments * passes::kCaptureSegmentBytes;
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, tiny);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    for (int frame = 0; frame < 2; ++frame) {
      render_frame(ctx(), renderer, executor, view);
      const auto& stats = renderer.shadows().frame_stats();
      ASSERT_EQ(stats.size(), scene.lights.size());
      for (const passes::LightShadowStats& light : stats) {
        const std::string where = "frame " + std::to_string(frame + 1) + ", " + light.light;
        EXPECT_TRUE(light.overflowed) << where;
        EXPECT_GT(light.capture_requested, light.capture_capacity) << where;
        EXPECT_EQ(light.capture_capacity, kTinySegments) << where;
        EXPECT_EQ(light.next_capture_capacity, kTinySegments) << where << ": growth must stop at the limit";
        std::cout << "[ overflow    ] " << where << ": asked for " << light.capture_requested << ", room for "
                  << light.capture_capacity << ", next " << light.next_capture_capacity << "\n";
      }
      // Dropped segments make shadows lighter, never invalid.
      EXPECT_TRUE(all_finite(gpu::read_image(ctx(), renderer.hdr(), renderer::SceneRenderer::kOutputLayout)))
          << "frame " << frame + 1 << ": NaN or Inf in the HDR image";
      const std::vector<std::vector<uint8_t>> maps = read_maps(ctx(), renderer.shadows());
      for (uint32_t light = 0; light < maps.size(); ++light)
        EXPECT_EQ(invalid_stored_curves(maps[light], renderer.shadows().map_layout(light),
                                        renderer.shadows().light_views()[light]),
                  size_t(0))
            << "frame " << frame + 1 << ", light " << light << ": AVSM map texels whose nodes are not a curve";
    }
  }
  {
    // One segment per march sample makes the smoke ask for far more than the first
    // guess (8 segments per texel), so the first frame overflows and the second grows.
    passes::ShadowOptions roomy;
    roomy.smoke_samples_per_segment = 1;
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, roomy);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    render_frame(ctx(), renderer, executor, view);
    const std::vector<passes::LightShadowStats> first = renderer.shadows().frame_stats();
    render_frame(ctx(), renderer, executor, view);
    const std::vector<passes::LightShadowStats> second = renderer.shadows().frame_stats();
    bool any_grew = false;
    for (size_t i = 0; i < first.size(); ++i) {
      const std::string where = first[i].light;
      std::cout << "[ growth      ] " << where << ": frame 1 asked for " << first[i].capture_requested << " with room for "
                << first[i].capture_capacity << "; frame 2 asked for " << second[i].capture_requested
                << " with room for " << second[i].capture_capacity << "\n";
      if (first[i].overflowed) {
        any_grew = true;
        EXPECT_GE(first[i].next_capture_capacity, first[i].capture_requested) << where;
        EXPECT_GT(second[i].capture_capacity, first[i].capture_capacity) << where;
      }
      EXPECT_EQ(second[i].capture_capacity, first[i].next_capture_capacity) << where;
      EXPECT_GE(second[i].capture_capacity, second[i].capture_requested) << where;
      EXPECT_FALSE(second[i].overflowed) << where;
    }
    EXPECT_TRUE(any_grew) << "the first frame should overflow the first guess for at least one light";
    EXPECT_TRUE(all_finite(gpu::read_image(ctx(), renderer.hdr(), renderer::SceneRenderer::kOutputLayout)));
  }
}


// ---- 7. The fixed-memory build (shadow.build "fixed") ----

// Probe transmittances of every light on a grid through the scene's bounds.
std::vector<std::vector<float>> probe_grid(gpu::Context& ctx, const gpu::ShaderLibrary& shaders,
                                           const scene::Scene& scene, std::vector<passes::LightShadowStats>* stats = nullptr) {
  std::vector<glm::vec3> probes;
  const glm::vec3 lo = scene.bounds.min, size = scene.bounds.max - scene.bounds.min;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 10; ++k)
        probes.push_back(lo + size * glm::vec3((i + 0.5f) / 10, (j + 0.5f) / 6, (k + 0.5f) / 10) * 0.96f + 0.02f * size);
  renderer::SceneRenderer renderer(ctx, shaders, scene, kFrameWidth, kFrameHeight);
  renderer.set_probes(probes);
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  render_frame(ctx, renderer, executor, passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight));
  if (stats) *stats = renderer.shadows().frame_stats();
  return renderer.probe_results();
}

scene::Scene with_build(scene::Scene scene, scene::ShadowBuild build) {
  for (scene::Light& light : scene.lights) light.shadow.build = build;
  return scene;
}

// Fixed inserts hair in segment order rather than depth order, and the opaque caster
// as one blocker: a different curve than the sorted lists', within a small error.
TEST_F(AvsmShadowTest, FixedBuildMatchesSortedListsAtProbes) {
  const scene::Scene scene = default_scene(8, 128);
  std::vector<passes::LightShadowStats> fixed_stats;
  const auto lists = probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::lists));
  const auto fixed = probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::fixed), &fixed_stats);
  ASSERT_EQ(lists.size(), fixed.size());
  for (size_t light = 0; light < lists.size(); ++light) {
    double sum = 0.0, worst = 0.0;
    size_t partial = 0;
    for (size_t i = 0; i < lists[light].size(); ++i) {
      const double error = std::abs(double(fixed[light][i]) - lists[light][i]);
      worst = std::max(worst, error);
      if (lists[light][i] > 0.0f && lists[light][i] < 1.0f) sum += error, ++partial;
    }
    const double mean = partial ? sum / double(partial) : 0.0;
    std::cout << "[ fixed build ] light " << light << ": mean |T_fixed - T_lists| " << mean << " over " << partial
              << " partly shadowed probes, max " << worst << "\n";
    EXPECT_GT(partial, 20u) << "light " << light << ": the grid should see partial shadow";
    EXPECT_LT(mean, 0.005) << "light " << light;  // measured 0.0020 and 0.0003 (128^2, AVSM-8)
    ASSERT_TRUE(fixed_stats[light].fixed_build);
    EXPECT_GT(fixed_stats[light].fixed_build->inserted_segments, 0u);
    EXPECT_EQ(fixed_stats[light].capture_bytes, 0u) << "no lists in the fixed build";
  }
}

// Opacity shadow maps and Fourier opacity maps are sums over the segments, so built
// straight from the casters they should be the list-built maps but for the opaque
// caster: the lists add every opaque layer (each capped at optical depth 12), the
// direct build only the nearest one and nothing behind it, where light is gone anyway.
TEST_F(AvsmShadowTest, OpacityMapsBuiltDirectlyMatchTheirListBuilds) {
  for (const char* technique : {"osm", "fom"}) {
    scene::Scene scene = default_scene(8, 128);  // (at 64^2 the lists' first frame overflows)
    for (scene::Light& light : scene.lights) light.shadow.technique = technique;
    const auto lists = probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::lists));
    const auto direct = probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::fixed));
    ASSERT_EQ(lists.size(), direct.size());
    for (size_t light = 0; light < lists.size(); ++light) {
      double sum = 0.0, worst = 0.0;
      size_t lit = 0;
      for (size_t i = 0; i < lists[light].size(); ++i) {
        if (lists[light][i] <= 1e-3f) continue;  // behind opaque casters: both dark
        const double error = std::abs(double(direct[light][i]) - lists[light][i]);
        sum += error, worst = std::max(worst, error), ++lit;
      }
      const double mean = lit ? sum / double(lit) : 0.0;
      std::cout << "[ direct " << technique << " ] light " << light << ": mean |T_direct - T_lists| " << mean
                << " over " << lit << " lit probes, max " << worst << "\n";
      EXPECT_GT(lit, 100u);
      EXPECT_LT(mean, 1e-3) << technique << ", light " << light;  // measured 3e-7 to 1.1e-4 (128^2)
    }
  }
}

// Strands each one segment long across the whole scene: every segment overlaps a row
// of tiles, far more than the kHairBinEntriesPerSegment entries the bins hold per
// segment, so bins do not fit. Those tiles walk every segment instead (reported), and
// the map still matches the lists: nothing is dropped.
TEST_F(AvsmShadowTest, FixedBuildBinsThatDoNotFitWalkEverySegment) {
  scene::Scene scene = default_scene(8, 64);
  scene::HairGroom groom;
  groom.name = "long strands";
  groom.width_kind = scene::StrandWidth::absolute;
  const glm::vec3 lo = scene.bounds.min, hi = scene.bounds.max;
  groom.strand_offsets.push_back(0);
  for (int s = 0; s < 12; ++s) {
    const float z = lo.z + (hi.z - lo.z) * (s + 0.5f) / 12.0f, y = 1.0f + 0.1f * float(s);
    groom.points.push_back({lo.x + 0.1f, y, z});
    groom.points.push_back({hi.x - 0.1f, y, z + 0.3f});
    groom.strand_offsets.push_back(uint32_t(groom.points.size()));
    groom.strand_width.push_back(0.02f);
    groom.strand_opacity.push_back(0.5f);
    groom.strand_color.push_back(scene::kDefaultStrandColor);
  }
  for (const glm::vec3& p : groom.points) groom.bounds.extend(p);
  scene.hair = {groom};
  std::vector<passes::LightShadowStats> stats;
  const auto lists = probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::lists));
  const auto fixed = probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::fixed), &stats);
  for (size_t light = 0; light < scene.lights.size(); ++light) {
    const passes::FixedBuildStats& f = *stats[light].fixed_build;
    double sum = 0.0;
    size_t partial = 0;
    for (size_t i = 0; i < lists[light].size(); ++i)
      if (lists[light][i] > 0.0f && lists[light][i] < 1.0f)
        sum += std::abs(double(fixed[light][i]) - lists[light][i]), ++partial;
    const double mean = partial ? sum / double(partial) : 0.0;
    std::cout << "[ bins full   ] light " << light << ": " << f.hair_bin_requested << " entries asked for, room for "
              << f.hair_bin_capacity << ", " << f.tiles_walked << " tiles walked every segment; mean |T_fixed - T_lists| "
              << mean << " over " << partial << " partly shadowed probes\n";
    EXPECT_GT(f.hair_bin_requested, f.hair_bin_capacity) << "light " << light << ": the bins should not fit";
    EXPECT_GT(f.tiles_walked, 0u) << "light " << light;
    EXPECT_FALSE(stats[light].lost_shadowing()) << "light " << light;
    EXPECT_LT(mean, 0.005) << "light " << light;
  }
}

TEST_F(AvsmShadowTest, FixedBuildIsBitIdenticalAcrossRunsWithoutSort) {
  scene::Scene scene = with_build(default_scene(8, 64), scene::ShadowBuild::fixed);
  for (scene::Light& light : scene.lights) light.shadow.sort = false;
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  std::vector<std::vector<uint8_t>> runs[2];
  for (auto& maps : runs) {
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    render_frame(ctx(), renderer, executor, view);
    maps = read_maps(ctx(), renderer.shadows());
  }
  ASSERT_EQ(runs[0].size(), scene.lights.size());
  for (size_t light = 0; light < runs[0].size(); ++light)
    EXPECT_TRUE(runs[0][light] == runs[1][light]) << "light " << light << ": fixed builds of one scene differ";
}

// The same strands pressed ten times closer together along x and z: about ten times
// the hair layers per light texel. The fixed build's memory is the map, the depth
// image and bins sized by the segment count, so it stays the same, and nothing is
// dropped (a tile whose bin does not fit walks every segment).
TEST_F(AvsmShadowTest, FixedBuildMemoryDoesNotGrowWithHairLayers) {
  const scene::Scene scene = default_scene(8, 64);
  ASSERT_FALSE(scene.hair.empty());
  scene::Scene dense = scene;
  for (scene::HairGroom& groom : dense.hair) {
    const glm::vec3 centre = groom.bounds.center();
    for (glm::vec3& p : groom.points) p = centre + (p - centre) * glm::vec3(0.1f, 1.0f, 0.1f);
  }
  std::vector<passes::LightShadowStats> sparse_fixed, dense_fixed, sparse_lists, dense_lists;
  probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::fixed), &sparse_fixed);
  probe_grid(ctx(), shaders(), with_build(dense, scene::ShadowBuild::fixed), &dense_fixed);
  probe_grid(ctx(), shaders(), with_build(scene, scene::ShadowBuild::lists), &sparse_lists);
  probe_grid(ctx(), shaders(), with_build(dense, scene::ShadowBuild::lists), &dense_lists);
  for (size_t light = 0; light < scene.lights.size(); ++light) {
    const passes::FixedBuildStats& a = *sparse_fixed[light].fixed_build;
    const passes::FixedBuildStats& b = *dense_fixed[light].fixed_build;
    std::cout << "[ hair layers ] light " << light << ": lists asked for " << sparse_lists[light].capture_requested
              << " -> " << dense_lists[light].capture_requested << " segments; fixed "
              << a.transient_bytes() + sparse_fixed[light].map_bytes << " -> "
              << b.transient_bytes() + dense_fixed[light].map_bytes << " bytes, inserted " << a.inserted_segments
              << " -> " << b.inserted_segments << ", tiles walked whole " << b.tiles_walked << "\n";
    EXPECT_EQ(a.transient_bytes(), b.transient_bytes()) << "light " << light;
    EXPECT_EQ(sparse_fixed[light].map_bytes, dense_fixed[light].map_bytes) << "light " << light;
    EXPECT_FALSE(dense_fixed[light].lost_shadowing()) << "light " << light;
    EXPECT_GT(b.hair_bin_requested, 0u) << "light " << light;
  }
}

// ---- 8. The fixed build against a CPU reference on random casters ----
//
// The CPU reproduces common/fixed_build.glsl texel by texel: the nearest opaque caster
// (the light depth raster, redone here by point-in-triangle tests at texel centres) as
// one blocking segment, then every hair segment whose ribbon covers the texel centre in
// segment order (footprints from passes/frame/hair_geometry.h, the file the shaders include),
// each inserted with the C++ AVSM core. Texels where a decision sits within rounding of
// its threshold are marked: there the GPU may legitimately decide the other way.

// Random hair strands (random-walk polylines; widths from under a tenth of a 64^2 map
// texel to two texels, so both widened and wide ribbons; opacities 0.05..0.95) over two
// opaque meshes: a randomly turned box among the strands and a few random triangles
// under them.
scene::Scene random_caster_scene(uint32_t seed) {
  std::mt19937 rng(seed);
  auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  scene::Scene scene;
  scene.file = "random casters (built in the test)";
  scene.materials.push_back({});

  auto add_mesh = [&](const std::string& name, const std::vector<glm::vec3>& positions,
                      const std::vector<uint32_t>& indices) {
    scene::Mesh mesh;
    mesh.name = name;
    mesh.positions = positions;
    mesh.normals.assign(positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
    mesh.indices = indices;
    for (const glm::vec3& p : positions) mesh.bounds.extend(p);
    scene.bounds.extend(mesh.bounds);
    scene.meshes.push_back(std::move(mesh));
  };
  {
    const glm::vec3 centre(uniform(-0.3f, 0.3f), uniform(-0.2f, 0.2f), uniform(-0.3f, 0.3f));
    const glm::vec3 half(uniform(0.2f, 0.45f), uniform(0.2f, 0.45f), uniform(0.2f, 0.45f));
    const glm::vec3 axis = glm::normalize(glm::vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) + glm::vec3(1e-3f));
    const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), uniform(0.3f, 1.2f), axis));
    std::vector<glm::vec3> corners;
    for (int c = 0; c < 8; ++c)
      corners.push_back(centre + turn * (half * glm::vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1)));
    add_mesh("box", corners, {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                              2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3});
  }
  {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    for (int t = 0; t < 8; ++t) {
      const glm::vec3 at(uniform(-0.8f, 0.8f), uniform(-0.9f, -0.5f), uniform(-0.8f, 0.8f));
      for (int k = 0; k < 3; ++k) {
        indices.push_back(uint32_t(positions.size()));
        positions.push_back(at + glm::vec3(uniform(-0.6f, 0.6f), uniform(-0.15f, 0.15f), uniform(-0.6f, 0.6f)));
      }
    }
    add_mesh("triangles", positions, indices);
  }

  scene::HairGroom groom;
  groom.name = "random strands";
  groom.width_kind = scene::StrandWidth::absolute;
  groom.strand_offsets.push_back(0);
  for (int s = 0; s < 240; ++s) {
    glm::vec3 p(uniform(-0.6f, 0.6f), uniform(0.0f, 0.8f), uniform(-0.6f, 0.6f));
    const int points = std::uniform_int_distribution<int>(3, 10)(rng);
    for (int i = 0; i < points; ++i) {
      groom.points.push_back(p);
      p += glm::vec3(uniform(-0.12f, 0.12f), uniform(-0.15f, 0.03f), uniform(-0.12f, 0.12f));
    }
    groom.strand_offsets.push_back(uint32_t(groom.points.size()));
    groom.strand_width.push_back(std::exp(uniform(std::log(0.005f), std::log(0.15f))));
    groom.strand_opacity.push_back(uniform(0.05f, 0.95f));
    groom.strand_color.push_back(scene::kDefaultStrandColor);
  }
  scene::validate_groom(groom, scene.file);
  scene.bounds.extend(groom.bounds);
  scene.hair.push_back(std::move(groom));

  auto light = [](const std::string& name) {
    scene::Light l;
    l.name = name;
    l.shadow.technique = "avsm";
    l.shadow.nodes = 8;
    l.shadow.resolution = 64;
    l.shadow.filter = scene::ShadowFilter::point;
    l.shadow.build = scene::ShadowBuild::fixed;
    // Around the whole scene: the tolerances below were measured with these footprints
    // (a cone narrowed to the casters has more texels at 16-bit rounding distance).
    l.shadow.fit = scene::ShadowFit::scene;
    return l;
  };
  scene::Light sun = light("sun");
  sun.direction = glm::normalize(glm::vec3(uniform(-0.5f, 0.5f), -1.0f, uniform(-0.5f, 0.5f)));
  scene.lights.push_back(sun);
  scene::Light spot = light("spot");
  spot.type = scene::LightType::spot;
  spot.position = glm::vec3(uniform(-1.0f, 1.0f), 2.5f, uniform(-1.0f, 1.0f));
  spot.direction = glm::normalize(scene.bounds.center() - spot.position);
  spot.outer_cone_angle = glm::radians(40.0f);
  spot.inner_cone_angle = glm::radians(30.0f);
  scene.lights.push_back(spot);

  scene::Camera camera;
  camera.position = glm::vec3(0.0f, 1.0f, 4.0f);
  camera.target = scene.bounds.center();
  scene.cameras.push_back(camera);
  return scene;
}

// Same casters, same order, same core: only float rounding differs (contracted
// multiply-adds, the GPU's own inverse of the light matrix, the rasterizer's depth
// plane against the CPU's barycentrics): node depths a few ulps apart. That moves a
// node inside a segment's ramp (one texel thick: 1 - T over about 0.07 world units
// here) along it, up to 15 per unit times those ulps of depths near 5 (5e-7 each), so
// node transmittances differ by about 1e-5. Stored at 16 bits (1.5e-5 a step), most
// round to the same node: measured 99.3% of 24576 texels bit-identical, all clear of
// near ties within two steps (3.1e-5). kRoundingBound leaves room for a few steps.
constexpr float kFixedBuildTolerance = 1e-5f;
constexpr float kRoundingBound = 1e-4f;

// Per texel, the largest difference of a stored node: depth relative to the light's
// far depth (depths are world distances up to it), transmittance absolute.
float texel_error(const StoredCurve& got, const StoredCurve& want, float far_depth) {
  float error = 0.0f;
  for (size_t i = 0; i < got.depth.size(); ++i) {
    error = std::max(error, std::abs(got.depth[i] - want.depth[i]) / far_depth);
    error = std::max(error, std::abs(got.trans[i] - want.trans[i]));
  }
  return error;
}

// Decisions that sit within rounding of their threshold, where the GPU may decide the
// other way (one bit each):
enum NearTie : uint8_t {
  kTieOpaqueEdge = 1,   // a texel centre within kOpaqueEdgeTie texels of a triangle's edge
  kTieHairEdge = 2,     // ... within kHairEdgeTie of a ribbon triangle's edge
  kTieBlocker = 4,      // a hair crossing at the opaque blocker's far end (rejected or not)
  kTieCompression = 8,  // two removal costs closer than the node values' tolerance can tell
};
// The rasterizer snaps vertices to 1/256 texel (lavapipe: 8 subpixel bits) ...
constexpr float kOpaqueEdgeTie = 1e-2f;
// ... while the hair footprints are the GPU's own arithmetic (passes/frame/hair_geometry.h),
// off by a few ulps of texel coordinates below 64 (about 1e-5).
constexpr float kHairEdgeTie = 1e-4f;

// Distance in texels from p to the line through a and b.
float distance_to_edge(glm::vec2 a, glm::vec2 b, glm::vec2 p) {
  return std::abs(hair_geometry::footprint_edge(a, b, p)) / std::max(glm::length(b - a), 1e-30f);
}

// Inserts as core::avsm_insert_segment does (uncompressed first, then the same
// compression steps) and says whether a step was a near tie: another interior node's
// removal cost within what node values `slack` apart could change (4 slack per unit
// of the two spans), so the GPU may remove that one instead. Nodes in a flat stretch
// (three equal transmittances, 0 behind a blocker say) cost exactly 0 on both sides.
bool insert_marking_ties(AvsmCurve& curve, float entry, float exit_depth, float transmittance, int nodes,
                         float slack) {
  core::avsm_insert_segment(curve, entry, exit_depth, transmittance, nodes + 2);  // room for both new nodes
  bool tie = false;
  auto uncertainty = [&](int i) {
    const bool flat = curve.trans[i - 1] == curve.trans[i] && curve.trans[i] == curve.trans[i + 1];
    return flat ? 0.0f : 4.0f * slack * (curve.depth[i + 1] - curve.depth[i - 1]);
  };
  while (curve.count > nodes && curve.count > 2) {
    int cheapest = 1;  // as avsm_compress_once chooses
    for (int i = 2; i + 1 < curve.count; ++i)
      if (core::avsm_removal_cost(curve, i) < core::avsm_removal_cost(curve, cheapest)) cheapest = i;
    const float cost = core::avsm_removal_cost(curve, cheapest);
    for (int i = 1; i + 1 < curve.count; ++i)
      tie = tie || (i != cheapest &&
                    core::avsm_removal_cost(curve, i) - cost <= uncertainty(i) + uncertainty(cheapest));
    core::avsm_compress_once(curve, nodes);
  }
  return tie;
}

enum class HairOrder { segments, reversed };

struct CpuFixedBuild {
  std::vector<AvsmCurve> curves;  // resolution^2, row by row
  std::vector<uint8_t> ties;      // per texel, NearTie bits
  uint64_t inserted = 0;          // segments that went into curves (the GPU's inserted_segments)
  uint64_t inserted_at_edge_ties = 0;  // ... that texels with edge or blocker ties may take or not
  uint64_t opaque_texels = 0, hair_texels = 0, compressed_texels = 0;
};

// The fixed build of `scene`'s meshes and hair for `light`, texel by texel as
// common/fixed_build.glsl builds it (no smoke).
CpuFixedBuild cpu_fixed_build(const scene::Scene& scene, const passes::LightView& light, int nodes,
                              HairOrder order = HairOrder::segments) {
  const int res = int(light.resolution);
  const size_t texels = size_t(res) * size_t(res);
  auto centre_of = [](int x, int y) { return glm::vec2(float(x) + 0.5f, float(y) + 0.5f); };
  CpuFixedBuild out;
  out.ties.assign(texels, 0);

  // 1. Opaque: the nearest light-clip z per texel centre, both faces, cleared to 1
  // (passes/shadows/fixed_build/light_depth_pass.h).
  std::vector<float> z_buffer(texels, 1.0f);
  for (const scene::Mesh& mesh : scene.meshes)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      glm::vec2 screen[3];
      float z[3];
      for (int k = 0; k < 3; ++k) {
        const glm::vec4 clip = light.light_from_world * glm::vec4(mesh.positions[mesh.indices[t + k]], 1.0f);
        screen[k] = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * float(res);
        z[k] = clip.z / clip.w;
      }
      const float area = hair_geometry::footprint_edge(screen[0], screen[1], screen[2]);
      if (area == 0.0f) continue;
      const glm::vec2 lo = glm::min(glm::min(screen[0], screen[1]), screen[2]);
      const glm::vec2 hi = glm::max(glm::max(screen[0], screen[1]), screen[2]);
      for (int y = std::max(0, int(std::floor(lo.y)) - 1); y <= std::min(res - 1, int(hi.y) + 1); ++y)
        for (int x = std::max(0, int(std::floor(lo.x)) - 1); x <= std::min(res - 1, int(hi.x) + 1); ++x) {
          const glm::vec2 p = centre_of(x, y);
          const size_t texel = size_t(y) * res + size_t(x);
          for (int k = 0; k < 3; ++k)
            if (distance_to_edge(screen[k], screen[(k + 1) % 3], p) < kOpaqueEdgeTie) out.ties[texel] |= kTieOpaqueEdge;
          const glm::vec3 w = glm::vec3(hair_geometry::footprint_edge(screen[1], screen[2], p),
                                        hair_geometry::footprint_edge(screen[2], screen[0], p),
                                        hair_geometry::footprint_edge(screen[0], screen[1], p)) /
                              area;
          if (w.x < 0.0f || w.y < 0.0f || w.z < 0.0f) continue;
          const float depth = w.x * z[0] + w.y * z[1] + w.z * z[2];
          if (depth >= 0.0f && depth < z_buffer[texel]) z_buffer[texel] = depth;
        }
    }

  // 2. Hair: every texel's crossings in segment order (the renderer's: grooms, strands,
  // points; passes/camera/hair/hair_pass.cpp), footprints and coverage as the shaders compute them.
  std::vector<std::vector<glm::vec2>> crossings(texels);  // (depth, transmittance)
  const glm::vec3 facing = passes::hair_ribbon_facing_point(light);
  struct SegmentRef {
    const scene::HairGroom* groom;
    size_t strand;
    uint32_t point;
  };
  std::vector<SegmentRef> segments;
  for (const scene::HairGroom& groom : scene.hair)
    for (size_t s = 0; s < groom.strand_count(); ++s)
      for (uint32_t p = groom.strand_offsets[s]; p + 1 < groom.strand_offsets[s + 1]; ++p)
        segments.push_back({&groom, s, p});
  if (order == HairOrder::reversed) std::reverse(segments.begin(), segments.end());
  for (const SegmentRef& s : segments) {
    const hair_geometry::HairFootprint f = hair_geometry::hair_footprint_of(
        s.groom->points[s.point], s.groom->points[s.point + 1], s.groom->strand_width[s.strand],
        s.groom->strand_opacity[s.strand], light.light_from_world, facing, light.depth_plane, float(res));
    const glm::ivec4 box = hair_geometry::hair_footprint_texels(f, res);
    const glm::vec2 c[4] = {{f.x[0], f.y[0]}, {f.x[1], f.y[1]}, {f.x[2], f.y[2]}, {f.x[3], f.y[3]}};
    for (int y = box.y; y <= box.w; ++y)
      for (int x = box.x; x <= box.z; ++x) {
        const glm::vec2 p = centre_of(x, y);
        const size_t texel = size_t(y) * res + size_t(x);
        float near = distance_to_edge(c[0], c[2], p);  // the two triangles' shared edge
        for (int k = 0; k < 4; ++k) near = std::min(near, distance_to_edge(c[k], c[(k + 1) % 4], p));
        if (near < kHairEdgeTie) out.ties[texel] |= kTieHairEdge;
        float depth;
        if (hair_geometry::hair_footprint_covers(f, p, depth)) crossings[texel].emplace_back(depth, 1.0f - f.opacity);
      }
  }

  // 3. Each texel's curve: the opaque blocker, then the hair in front of its far end.
  out.curves.reserve(texels);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      const size_t texel = size_t(y) * res + size_t(x);
      AvsmCurve curve = core::avsm_clear(light.far_depth);
      float blocker_end = 3.4e38f;
      int inserted = 0;
      bool tie = false;
      if (z_buffer[texel] < 1.0f) {
        const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / float(res) * 2.0f - 1.0f;
        const glm::vec4 world = light.world_from_light * glm::vec4(ndc, z_buffer[texel], 1.0f);
        const float depth = light.depth(glm::vec3(world) / world.w);
        blocker_end = depth + light.texel_size(depth);
        tie = insert_marking_ties(curve, depth, blocker_end, 0.0f, nodes, kFixedBuildTolerance) || tie;
        ++inserted;
        ++out.opaque_texels;
      }
      for (const glm::vec2& c : crossings[texel]) {
        const float depth = c.x;
        if (std::abs(depth - blocker_end) <= kFixedBuildTolerance * light.far_depth) out.ties[texel] |= kTieBlocker;
        if (depth >= blocker_end) continue;  // behind the opaque caster
        tie = insert_marking_ties(curve, depth, depth + light.texel_size(depth), c.y, nodes, kFixedBuildTolerance) ||
              tie;
        ++inserted;
      }
      if (tie) out.ties[texel] |= kTieCompression;
      if (out.ties[texel] & (kTieOpaqueEdge | kTieHairEdge | kTieBlocker))
        out.inserted_at_edge_ties += 1 + crossings[texel].size();
      out.hair_texels += inserted > (z_buffer[texel] < 1.0f ? 1 : 0);
      out.compressed_texels += 2 * inserted + 1 > nodes;  // more nodes came in than the curve keeps
      out.inserted += uint64_t(inserted);
      out.curves.push_back(curve);
    }
  return out;
}

// Compares one light's map with the CPU reference; prints the figures.
void expect_fixed_build_matches_cpu(const scene::Scene& scene, const passes::LightView& view,
                                    const std::vector<uint8_t>& map, const passes::FixedBuildStats& stats,
                                    int nodes, const std::string& name) {
  const uint32_t res = view.resolution;
  const AvsmMapLayout layout{res, uint32_t(nodes), 1};
  std::vector<glm::vec4> texels(map.size() / sizeof(glm::vec4));
  std::memcpy(texels.data(), map.data(), texels.size() * sizeof(glm::vec4));
  const CpuFixedBuild cpu = cpu_fixed_build(scene, view, nodes);
  // The same comparison against the hair inserted back to front: order matters to
  // AVSM's compression, and the comparison must see it.
  const CpuFixedBuild reversed = cpu_fixed_build(scene, view, nodes, HairOrder::reversed);

  const size_t total = size_t(res) * res;
  size_t identical = 0, close = 0, rounding = 0, differing_at_ties = 0, differing_elsewhere = 0;
  size_t differing_reversed = 0, ties[4] = {}, any_tie = 0;
  float max_error = 0.0f, max_error_off_ties = 0.0f;
  int reported = 0;
  for (uint32_t y = 0; y < res; ++y)
    for (uint32_t x = 0; x < res; ++x) {
      const size_t texel = size_t(y) * res + x;
      const StoredCurve got = read_texel(texels, layout, 0, x, y, view.near_depth, view.far_depth);
      const StoredCurve want = stored_form(cpu.curves[texel], nodes, view.near_depth, view.far_depth);
      const float error = texel_error(got, want, view.far_depth);
      const uint8_t tie = cpu.ties[texel];
      for (int bit = 0; bit < 4; ++bit) ties[bit] += (tie >> bit) & 1;
      any_tie += tie != 0;
      max_error = std::max(max_error, error);
      if (!tie) max_error_off_ties = std::max(max_error_off_ties, error);
      if (bit_identical(got, want)) ++identical;
      else if (error <= kFixedBuildTolerance) ++close;
      else if (tie) ++differing_at_ties;
      else if (error <= kRoundingBound) ++rounding;
      else {
        ++differing_elsewhere;
        if (reported++ < 3)
          ADD_FAILURE() << name << ", texel (" << x << ", " << y << "): error " << error << "\n  GPU:" << describe(got)
                        << "\n  CPU:" << describe(want);
      }
      differing_reversed +=
          texel_error(got, stored_form(reversed.curves[texel], nodes, view.near_depth, view.far_depth), view.far_depth) >
          kFixedBuildTolerance;
    }
  std::cout << "[ fixed cpu   ] " << name << ": " << total << " texels (opaque " << cpu.opaque_texels << ", hair "
            << cpu.hair_texels << ", compressed " << cpu.compressed_texels << "): " << identical << " bit-identical, "
            << close << " within " << kFixedBuildTolerance << ", " << rounding << " within " << kRoundingBound
            << " (max off ties " << max_error_off_ties << "), " << differing_at_ties << " differ at near ties, "
            << differing_elsewhere << " elsewhere (max " << max_error << "); near ties " << any_tie << " (opaque edge "
            << ties[0] << ", hair edge " << ties[1] << ", blocker " << ties[2] << ", compression " << ties[3]
            << "); inserted GPU " << stats.inserted_segments << ", CPU " << cpu.inserted << "; hair reversed: "
            << differing_reversed << " texels differ\n";
  // Every texel clear of a near tie matches to rounding, 99% to the tolerance, and
  // the ties are few (measured up to 2.5%, most of them nodes inside ramps, whose
  // removal costs are rounding noise around 0).
  EXPECT_EQ(differing_elsewhere, 0u) << name;
  EXPECT_GE(double(identical + close), 0.99 * double(total)) << name;
  EXPECT_LE(any_tie, total * 3 / 100) << name;
  // The GPU took the same segments, but where a coverage or rejection was a near tie.
  const uint64_t off = stats.inserted_segments > cpu.inserted ? stats.inserted_segments - cpu.inserted
                                                              : cpu.inserted - stats.inserted_segments;
  EXPECT_LE(off, cpu.inserted_at_edge_ties) << name;
  // Not vacuous: opaque, hair and compression all occur, and hair order shows.
  EXPECT_GT(cpu.opaque_texels, total / 40) << name;
  EXPECT_GT(cpu.hair_texels, total / 10) << name;
  EXPECT_GT(cpu.compressed_texels, total / 25) << name;
  EXPECT_GT(differing_reversed, cpu.compressed_texels / 4) << name;
}

// A sun and a spot light (orthographic and perspective footprints), AVSM-8, 64^2, on
// three random scenes, set in turn on one renderer.
TEST_F(AvsmShadowTest, FixedBuildMatchesCpuReferenceOnRandomCasters) {
  constexpr int kNodes = 8;
  std::unique_ptr<renderer::SceneRenderer> renderer;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const scene::Scene scene = random_caster_scene(seed);
    if (renderer)
      renderer->set_scene(scene, {});
    else
      renderer = std::make_unique<renderer::SceneRenderer>(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    render_frame(ctx(), *renderer, executor, passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight));
    const std::vector<std::vector<uint8_t>> maps = read_maps(ctx(), renderer->shadows());
    const std::vector<passes::LightShadowStats>& stats = renderer->shadows().frame_stats();
    ASSERT_EQ(maps.size(), scene.lights.size());
    for (size_t light = 0; light < maps.size(); ++light) {
      const std::string name = "scene " + std::to_string(seed) + ", " + scene.lights[light].name;
      const passes::LightView& view = renderer->shadows().light_views().at(light);
      ASSERT_EQ(view.resolution, 64u) << name;
      ASSERT_TRUE(stats.at(light).fixed_build) << name;
      expect_fixed_build_matches_cpu(scene, view, maps[light], *stats[light].fixed_build, kNodes, name);
    }
  }
}
}  // namespace
}  // namespace avsm_shadow_test
}  // namespace avsm
