// The deep shadow map build (passes/shadows/techniques/dsm/dsm_build.comp) on the default
// scene's real capture lists: every texel's nodes against the C++ reference
// (passes/shadows/techniques/dsm/deep_shadow.h) built from the same lists, and against the exact curve of
// the texel's whole list, including the sun's hair texels of over a thousand segments.
#include <gtest/gtest.h>

#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <sstream>
#include <vector>

#include "passes/shadows/shadow_settings.h"
#include "gpu/transfer.h"
#include "passes/shadows/techniques/dsm/deep_shadow.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/frame/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "shared/map_layouts.h"
#include "support/gpu_test.h"

namespace avsm {
namespace deep_shadow_test {  // one per file: test targets are unity builds
namespace {

using DeepShadowTest = testing::GpuTest;
using core::DsmNode;
using shared::CaptureSegment;

constexpr uint32_t kFrameWidth = 64, kFrameHeight = 36;
constexpr uint32_t kResolution = 32;
constexpr float kError = 0.01f;

// What one texel's GPU nodes may differ from the C++ reference by: the same code, only
// float rounding (contracted multiply-adds in the device compiler) differs.
constexpr float kTransTolerance = 1e-5f;

template <typename T>
std::vector<T> read_as(gpu::Context& ctx, const gpu::Buffer& buffer) {
  const std::vector<uint8_t> bytes = gpu::read_buffer_bytes(ctx, buffer);
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

// Texel `index`'s nodes in a deep shadow map's words (layout: shared/map_layouts.h).
std::vector<DsmNode> map_nodes(const std::vector<uint32_t>& words, uint32_t resolution, uint32_t index) {
  const uint32_t first = words.at(shared::dsm_first_node_word(index)), count = words.at(shared::dsm_node_count_word(index));
  EXPECT_NE(count, shared::kDsmLost) << "texel " << index << ": the pool did not take it";
  std::vector<DsmNode> nodes(count);
  const size_t pool = shared::dsm_pool_base(resolution);
  EXPECT_LE(pool + 2 * (size_t(first) + count), words.size());
  std::memcpy(nodes.data(), words.data() + pool + 2 * size_t(first), count * sizeof(DsmNode));
  return nodes;
}

size_t list_length(const std::vector<CaptureSegment>& nodes, uint32_t head) {
  size_t length = 0;
  for (uint32_t node = head; node != shared::kListEnd; node = nodes[node].next) ++length;
  return length;
}

std::string describe(const std::vector<DsmNode>& nodes) {
  std::ostringstream out;
  for (size_t i = 0; i < std::min<size_t>(nodes.size(), 12); ++i) out << " (" << nodes[i].depth << ", " << nodes[i].trans << ")";
  if (nodes.size() > 12) out << " ... " << nodes.size() << " nodes";
  return out.str();
}

TEST_F(DeepShadowTest, BuildMatchesCppReferenceAndTheExactCurveOnTheDefaultScene) {
  scene::Scene scene = scene::load_scene(AVSM_DEFAULT_SCENE);
  ASSERT_FALSE(scene.lights.empty());
  // Dense deep shadow maps (the default scene's are paged), as --technique dsm gives.
  for (scene::Light& light : scene.lights)
    passes::apply_shadow_overrides(
        {.technique = "dsm", .resolution = int(kResolution), .parameters = {{"error", double(kError)}}}, light);
  // The lookups' copy of the lists is what the test reads back (the build's own lists are transient).
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, {.keep_reference = true});
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  // The first frames may overflow the capture's and the pool's first guesses and make
  // too few build dispatches; each grows for the next.
  const passes::ShadowMaps& shadows = renderer.shadows();
  auto lost_shadowing = [&] {
    return std::any_of(shadows.frame_stats().begin(), shadows.frame_stats().end(),
                       [](const passes::LightShadowStats& stats) { return stats.lost_shadowing(); });
  };
  for (int frame = 0; frame < 5; ++frame) {
    rg::Graph graph = renderer.build_frame(view);
    ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    renderer.finish_frame();
    if (!lost_shadowing()) break;
  }
  for (const passes::LightShadowStats& stats : shadows.frame_stats()) {
    ASSERT_FALSE(stats.lost_shadowing()) << stats.light << ": the comparison needs every segment and node";
    std::cout << "[ dsm build   ] " << stats.light << ": " << stats.dsm_pool->build_dispatches + 1
              << " dispatches, pool nodes " << stats.dsm_pool->requested_nodes << " of "
              << stats.dsm_pool->capacity_nodes << "\n";
  }

  // Texels whose exact curve has more nodes than the 18 the build used to hold (it kept
  // 16 and trimmed the rest by area before compressing).
  size_t longest_list = 0, long_curves = 0, texels = 0;
  for (uint32_t light = 0; light < shadows.light_count(); ++light) {
    const std::string name = scene.lights[light].name;
    const float far_depth = shadows.light_views()[light].far_depth;
    const std::vector<uint32_t> heads = read_as<uint32_t>(ctx(), shadows.looked_up_list_heads(light));
    const std::vector<CaptureSegment> list_nodes = read_as<CaptureSegment>(ctx(), shadows.looked_up_list_nodes(light));
    const std::vector<uint32_t> words = read_as<uint32_t>(ctx(), shadows.avsm_map(light));
    ASSERT_EQ(heads.size(), size_t(kResolution) * kResolution) << name;
    float worst_vs_reference = 0.0f, worst_vs_exact = 0.0f;
    size_t light_longest = 0, light_most_nodes = 0, light_long_curves = 0, exact_nodes = 0, kept_nodes = 0;
    for (uint32_t index = 0; index < heads.size(); ++index) {
      const std::string where = name + ", texel (" + std::to_string(index % kResolution) + ", " +
                                std::to_string(index / kResolution) + ")";
      const std::vector<DsmNode> got = map_nodes(words, kResolution, index);
      const std::vector<DsmNode> want = core::dsm_build_list(list_nodes, heads[index], far_depth, kError);
      // Same code, same lists: the same nodes.
      ASSERT_EQ(got.size(), want.size()) << where << "\n  GPU:" << describe(got) << "\n  C++:" << describe(want);
      for (size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].depth, want[i].depth) << where << " node " << i;
        worst_vs_reference = std::max(worst_vs_reference, std::abs(got[i].trans - want[i].trans));
        ASSERT_NEAR(got[i].trans, want[i].trans, kTransTolerance) << where << " node " << i;
      }
      // Within the error of the exact curve of the whole list, at its every node.
      const std::vector<core::DsmExactValue> exact = core::dsm_exact_values(list_nodes, heads[index], far_depth);
      const float error = core::dsm_max_error_at_exact_nodes(got, exact);
      worst_vs_exact = std::max(worst_vs_exact, error);
      ASSERT_LE(error, kError + 1e-5f) << where << ": " << list_length(list_nodes, heads[index]) << " segments, GPU:"
                                       << describe(got);
      light_longest = std::max(light_longest, list_length(list_nodes, heads[index]));
      light_most_nodes = std::max(light_most_nodes, got.size());
      light_long_curves += exact.size() > 18;
      exact_nodes += exact.size();
      kept_nodes += got.size();
    }
    std::cout << "[ dsm build   ] " << name << ": longest list " << light_longest << " segments, most nodes "
              << light_most_nodes << ", " << light_long_curves << " texels of over 18 exact nodes, nodes " << kept_nodes
              << " of " << exact_nodes << " exact; max |GPU - C++| "
              << worst_vs_reference << ", max |GPU - exact| " << worst_vs_exact << " (error " << kError << ")\n";
    longest_list = std::max(longest_list, light_longest);
    long_curves += light_long_curves;
    texels += heads.size();
  }
  // Not vacuous: the sun's hair texels hold over a thousand segments, and many exact
  // curves are longer than the build could hold before.
  EXPECT_GT(longest_list, 1000u);
  EXPECT_GT(long_curves, 100u);
  EXPECT_EQ(texels, size_t(shadows.light_count()) * kResolution * kResolution);
}

}  // namespace
}  // namespace deep_shadow_test
}  // namespace avsm
