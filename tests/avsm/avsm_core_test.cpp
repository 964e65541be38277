// The AVSM core (shaders/avsm/avsm_core.glsl) on the CPU, against the exact
// product of the inserted segments.
#include "passes/shadows/techniques/avsm/avsm_core.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace avsm {
namespace avsm_core_test {  // one per file: test targets are unity builds
namespace {

using core::AvsmCurve;

struct Segment {
  float entry, exit, exit_trans;
};

constexpr float kFar = 100.0f;

// Exact transmittance at d: the product of every segment's linear ramp.
float exact(const std::vector<Segment>& segments, float d) {
  float t = 1.0f;
  for (const Segment& s : segments) {
    if (d <= s.entry) continue;
    float length = s.exit - s.entry;
    t *= d >= s.exit || length <= 0.0f ? s.exit_trans : 1.0f + (s.exit_trans - 1.0f) * (d - s.entry) / length;
  }
  return t;
}

AvsmCurve build(const std::vector<Segment>& segments, int max_nodes) {
  AvsmCurve c = core::avsm_clear(kFar);
  for (const Segment& s : segments) core::avsm_insert_segment(c, s.entry, s.exit, s.exit_trans, max_nodes);
  return c;
}

std::vector<Segment> random_segments(std::mt19937& rng, int count, bool disjoint) {
  std::uniform_real_distribution<float> depth(1.0f, 90.0f), length(0.01f, 5.0f), trans(0.3f, 0.99f);
  std::vector<Segment> out;
  float cursor = 1.0f;
  for (int i = 0; i < count; ++i) {
    float entry = disjoint ? cursor : depth(rng);
    float exit = entry + (disjoint ? 80.0f / count * 0.5f : length(rng));
    cursor = entry + 80.0f / count;
    out.push_back({entry, exit, trans(rng)});
  }
  if (disjoint) std::shuffle(out.begin(), out.end(), rng);  // arrival order must not matter
  return out;
}

TEST(AvsmCore, ClearedCurveIsFullyLit) {
  AvsmCurve c = core::avsm_clear(kFar);
  EXPECT_EQ(c.count, 1);
  EXPECT_EQ(core::avsm_evaluate_linear(c, 0.0f), 1.0f);
  EXPECT_EQ(core::avsm_evaluate_linear(c, kFar * 2), 1.0f);
}

TEST(AvsmCore, OpaqueBlockerTakesTransmittanceToZeroAtItsExit) {
  AvsmCurve c = build({{10.0f, 10.01f, 0.0f}}, 8);
  EXPECT_EQ(core::avsm_evaluate_linear(c, 9.0f), 1.0f);
  EXPECT_EQ(core::avsm_evaluate_linear(c, 10.01f), 0.0f);
  EXPECT_EQ(core::avsm_evaluate_linear(c, 50.0f), 0.0f);
}

TEST(AvsmCore, EnoughNodesReproduceTheExactCurve) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    // Disjoint segments: the node curve is the exact product everywhere.
    std::vector<Segment> segments = random_segments(rng, 7, /*disjoint=*/true);
    AvsmCurve c = build(segments, 16);  // 1 + 2*7 = 15 nodes fit
    ASSERT_EQ(c.count, 15);
    for (float d = 0.0f; d < kFar; d += 0.37f)
      ASSERT_NEAR(core::avsm_evaluate_linear(c, d), exact(segments, d), 1e-5f) << "trial " << trial << " d " << d;
  }
}

// Where segments overlap, the product of two ramps is quadratic and the curve,
// linear between nodes, approximates it: exactness holds only for disjoint
// segments (above) and behind all of them (the last node, below).

TEST(AvsmCore, CompressionKeepsFirstAndLastNodesAndTheBudget) {
  std::mt19937 rng(3);
  for (int nodes : {4, 8, 12, 16}) {
    for (int trial = 0; trial < 100; ++trial) {
      std::vector<Segment> segments = random_segments(rng, 40, /*disjoint=*/false);
      AvsmCurve c = build(segments, nodes);
      ASSERT_LE(c.count, nodes);
      float front = kFar;
      for (const Segment& s : segments) front = std::min(front, s.entry);
      EXPECT_EQ(c.depth[0], front) << "the first node is the front-most entry";
      EXPECT_EQ(c.depth[c.count - 1], kFar) << "the last node is the far node";
      // Behind everything the shadow is exact: the last node is never compressed.
      EXPECT_NEAR(c.trans[c.count - 1], exact(segments, kFar), 1e-5f);
      for (int i = 1; i < c.count; ++i) {
        EXPECT_GE(c.depth[i], c.depth[i - 1]);
        EXPECT_LE(c.trans[i], c.trans[i - 1] + 1e-6f) << "transmittance never rises";
      }
    }
  }
}

TEST(AvsmCore, NodesNeverMove) {
  // Every node of a compressed curve sits at a depth some segment inserted.
  std::mt19937 rng(5);
  std::vector<Segment> segments = random_segments(rng, 30, false);
  AvsmCurve c = build(segments, 8);
  for (int i = 0; i < c.count; ++i) {
    bool inserted = c.depth[i] == kFar;
    for (const Segment& s : segments) inserted |= c.depth[i] == s.entry || c.depth[i] == s.exit;
    EXPECT_TRUE(inserted) << "node " << i << " at " << c.depth[i];
  }
}

TEST(AvsmCore, RemovesTheNodeThatChangesTheAreaLeast) {
  // Four nodes: (0,1) (1,0.5) (2,0.45) (3,0.45); removing node 2 costs less
  // than node 1, as in the paper's Figure 2.
  AvsmCurve c = core::avsm_clear(kFar);
  c.count = 4;
  float depth[4] = {0.0f, 1.0f, 2.0f, 3.0f}, trans[4] = {1.0f, 0.5f, 0.45f, 0.45f};
  for (int i = 0; i < 4; ++i) c.depth[i] = depth[i], c.trans[i] = trans[i];
  EXPECT_LT(core::avsm_removal_cost(c, 2), core::avsm_removal_cost(c, 1));
  core::avsm_compress(c, 3);
  ASSERT_EQ(c.count, 3);
  EXPECT_EQ(c.depth[1], 1.0f);
}

TEST(AvsmCore, MoreNodesMeanLessError) {
  std::mt19937 rng(9);
  double error[4] = {0, 0, 0, 0};
  const int node_counts[4] = {4, 8, 12, 16};
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<Segment> segments = random_segments(rng, 24, false);
    std::sort(segments.begin(), segments.end(), [](auto& a, auto& b) { return a.entry < b.entry; });
    for (int k = 0; k < 4; ++k) {
      AvsmCurve c = build(segments, node_counts[k]);
      for (float d = 0.0f; d < kFar; d += 0.5f) error[k] += std::abs(core::avsm_evaluate_linear(c, d) - exact(segments, d));
    }
  }
  EXPECT_GT(error[0], error[1]);
  EXPECT_GT(error[1], error[2]);
  EXPECT_GT(error[2], error[3]);
}

}  // namespace
}  // namespace avsm_core_test
}  // namespace avsm
