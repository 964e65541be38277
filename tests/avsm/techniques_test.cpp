// The comparison techniques' math on the CPU (shaders/techniques/*.glsl compiled as
// C++): deep shadow maps of lists of any length against their error threshold, opacity shadow maps
// and Fourier opacity maps against slabs and a sharp step with known transmittance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "passes/shadows/techniques/dsm/deep_shadow.h"
#include "passes/shadows/techniques/opacity_maps.h"

namespace avsm {
namespace techniques_test {  // one per file: test targets are unity builds
namespace {

using core::AvsmCurve;

constexpr float kFar = 100.0f;

// ---- Deep shadow maps ----

using core::DsmNode;
using shared::CaptureSegment;

// A list as the captures link it: each node points at the one appended before it.
struct List {
  std::vector<CaptureSegment> nodes;
  uint32_t head() const { return nodes.empty() ? shared::kListEnd : uint32_t(nodes.size() - 1); }
  void append(float entry, float exit_depth, float exit_trans) {
    nodes.push_back({entry, exit_depth, exit_trans, head()});
  }
};

// Overlapping segments anywhere in (1, kFar * 1.1), each letting through at least
// `min_trans`: some of zero length (steps), some running past the far depth (clamped
// there), some opaque.
List random_list(std::mt19937& rng, int max_segments, float min_trans = 0.0f) {
  std::uniform_int_distribution<int> count(0, max_segments);
  std::uniform_real_distribution<float> depth(1.0f, 1.1f * kFar), length(0.0f, 8.0f), trans(min_trans, 1.0f),
      u(0.0f, 1.0f);
  List list;
  for (int i = count(rng); i > 0; --i) {
    const float entry = depth(rng);
    const float kind = u(rng);
    list.append(entry, entry + (kind < 0.1f ? 0.0f : length(rng)), kind > 0.998f ? 0.0f : trans(rng));
  }
  return list;
}

TEST(DeepShadowMaps, CompressionOfListsOfAnyLengthStaysWithinItsErrorThreshold) {
  std::mt19937 rng(7);
  for (float error : {0.002f, 0.01f, 0.05f, 0.2f}) {
    size_t exact_nodes = 0, kept_nodes = 0, longest = 0;
    float worst = 0.0f;
    for (int trial = 0; trial < 60; ++trial) {
      // Long lists (hair) of light segments, whose product falls slowly.
      const List list = trial < 50 ? random_list(rng, 40) : random_list(rng, 2000, 0.997f);
      const std::vector<core::DsmExactValue> exact = core::dsm_exact_values(list.nodes, list.head(), kFar);
      const std::vector<DsmNode> compressed = core::dsm_build_list(list.nodes, list.head(), kFar, error);
      size_t steps = 0;  // exact nodes that are two (a step)
      for (const core::DsmExactValue& v : exact) steps += v.before != v.after;
      ASSERT_LE(compressed.size(), exact.size() + steps);
      ASSERT_GE(compressed.size(), 1u);
      EXPECT_EQ(compressed.back().depth, kFar) << "the last node is the far depth";
      for (size_t i = 1; i < compressed.size(); ++i) ASSERT_GE(compressed[i].depth, compressed[i - 1].depth);
      worst = std::max(worst, core::dsm_max_error_at_exact_nodes(compressed, exact));
      exact_nodes += exact.size() + steps;
      kept_nodes += compressed.size();
      longest = std::max(longest, list.nodes.size());
    }
    std::printf("[ dsm         ] error %.3f: worst %.5f, nodes kept %zu of %zu (lists up to %zu segments)\n", error,
                worst, kept_nodes, exact_nodes, longest);
    EXPECT_LE(worst, error + 1e-5f) << "error threshold " << error;
    EXPECT_GT(longest, 1000u);
    if (error >= 0.05f) {
      EXPECT_LT(kept_nodes, exact_nodes / 4) << "a loose threshold must drop most nodes";
    }
  }
}

// Where segments do not overlap, the AVSM core with room for every node is exact
// (where they do, it interpolates the curve so far at a new node, which the DSM does
// not): at a tiny threshold the DSM is its curve.
TEST(DeepShadowMaps, AtATinyThresholdDisjointSegmentsGiveTheAvsmCoresExactCurve) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> depth(1.0f, 1.1f * kFar), trans(0.0f, 1.0f);
  float worst = 0.0f;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<float> ends(2 * (trial % 8));
    for (float& end : ends) end = depth(rng);
    std::sort(ends.begin(), ends.end());
    List list;
    core::AvsmCurve exact = core::avsm_clear(kFar);
    for (size_t i = 0; i < ends.size(); i += 2) {
      list.append(ends[i], ends[i + 1], trans(rng));
      const CaptureSegment& s = list.nodes.back();
      core::avsm_insert_segment(exact, s.entry, s.exit_depth, s.exit_trans, 16);
    }
    ASSERT_LE(exact.count, 16);
    const std::vector<DsmNode> compressed = core::dsm_build_list(list.nodes, list.head(), kFar, 1e-6f);
    for (int i = 0; i <= 2000; ++i) {
      const float d = kFar * 1.05f * float(i) / 2000.0f;
      worst = std::max(worst, std::abs(core::dsm_evaluate(compressed, d) - core::avsm_evaluate_linear(exact, d)));
    }
  }
  std::printf("[ dsm         ] max |DSM at 1e-6 - AVSM core's exact curve| %.2g\n", worst);
  EXPECT_LE(worst, 1e-5f);
}

TEST(DeepShadowMaps, LokovicVeachCompressionOfACurveStaysWithinItsError) {
  // A smooth fall sampled densely: few lines suffice; each exact node stays within the error.
  std::vector<DsmNode> exact;
  for (int i = 0; i <= 1000; ++i) exact.push_back({float(i) * 0.1f, std::exp(-float(i) * 0.004f)});
  const std::vector<DsmNode> compressed = core::dsm_compress(exact, 0.01f);
  float worst = 0.0f;
  for (const DsmNode& n : exact) worst = std::max(worst, std::abs(core::dsm_evaluate(compressed, n.depth) - n.trans));
  EXPECT_LE(worst, 0.01f + 1e-6f);
  EXPECT_LT(compressed.size(), 20u);
  EXPECT_EQ(compressed.front().depth, 0.0f);
  EXPECT_EQ(compressed.back().depth, 100.0f);
}

TEST(DeepShadowMaps, AnOpaqueStepStaysSharp) {
  List list;
  list.append(50.0f, 50.0f, 0.0f);  // an opaque surface: a step at depth 50
  const std::vector<DsmNode> compressed = core::dsm_build_list(list.nodes, list.head(), kFar, 0.01f);
  EXPECT_NEAR(core::dsm_evaluate(compressed, 49.999f), 1.0f, 1e-6f);
  EXPECT_NEAR(core::dsm_evaluate(compressed, 50.001f), 0.0f, 1e-6f);
  ASSERT_EQ(compressed.size(), 3u);  // (50, 1), (50, 0), (far, 0)
}

TEST(DeepShadowMaps, AnEmptyListIsOneLitNode) {
  const std::vector<DsmNode> compressed = core::dsm_build_list({}, shared::kListEnd, kFar, 0.01f);
  ASSERT_EQ(compressed.size(), 1u);
  EXPECT_EQ(compressed[0].depth, kFar);
  EXPECT_EQ(compressed[0].trans, 1.0f);
}

// ---- Opacity shadow maps and Fourier opacity maps ----

struct Segment {
  float z0, z1, exit_trans;  // normalised depths
};

// A homogeneous slab [z0, z1] of total optical depth `tau`, as `pieces` consecutive segments.
std::vector<Segment> slab(float z0, float z1, float tau, int pieces) {
  std::vector<Segment> segments;
  for (int i = 0; i < pieces; ++i) {
    const float a = z0 + (z1 - z0) * float(i) / float(pieces), b = z0 + (z1 - z0) * float(i + 1) / float(pieces);
    segments.push_back({a, b, std::exp(-tau / float(pieces))});
  }
  return segments;
}

float slab_truth(float z0, float z1, float tau, float z) {
  return std::exp(-tau * std::clamp((z - z0) / (z1 - z0), 0.0f, 1.0f));
}

// An opacity shadow map texel built and looked up as the GPU does (osm_build.comp, shadow_lookup.glsl).
struct OsmTexel {
  int planes;
  std::vector<float> tau;
  OsmTexel(const std::vector<Segment>& segments, int planes_) : planes(planes_), tau(planes_, 0.0f) {
    for (const Segment& s : segments)
      for (int k = 1; k <= planes; ++k)
        tau[k - 1] += opacity::osm_plane_optical_depth(s.z0, s.z1, opacity::opacity_segment_optical_depth(s.exit_trans),
                                                       k, planes);
  }
  float transmittance(float z) const {
    const int plane = int(std::floor(std::clamp(z, 0.0f, 1.0f) * float(planes)));
    const float before = plane == 0 ? 0.0f : tau[plane - 1];
    return opacity::osm_transmittance(before, tau[std::min(plane, planes - 1)], z, planes);
  }
};

struct FomTexel {
  int terms;
  std::vector<float> a, b;
  FomTexel(const std::vector<Segment>& segments, int terms_) : terms(terms_), a(terms_, 0.0f), b(terms_, 0.0f) {
    for (const Segment& s : segments) {
      const float tau = opacity::opacity_segment_optical_depth(s.exit_trans);
      for (int k = 0; k < terms; ++k) {
        a[k] += opacity::fom_cosine_coefficient(s.z0, s.z1, tau, k);
        if (k > 0) b[k] += opacity::fom_sine_coefficient(s.z0, s.z1, tau, k);
      }
    }
  }
  float transmittance(float z) const {
    float optical_depth = 0.0f;
    for (int k = 0; k < terms; ++k) optical_depth += opacity::fom_term_optical_depth(a[k], b[k], k, terms, z);
    return opacity::fom_transmittance(optical_depth);
  }
};

TEST(OpacityShadowMaps, AHomogeneousSlabIsExactAtThePlanesAndCloseBetween) {
  // Slab edges on planes (0.25, 0.75 of 32 planes): the optical depth is linear between
  // planes, so interpolating it is exact everywhere.
  const OsmTexel aligned(slab(0.25f, 0.75f, 2.0f, 10), 32);
  for (int i = 0; i <= 1000; ++i) {
    const float z = float(i) / 1000.0f;
    EXPECT_NEAR(aligned.transmittance(z), slab_truth(0.25f, 0.75f, 2.0f, z), 1e-5f) << "z = " << z;
  }
  // Edges between planes: each kink is smoothed over its slice, so the optical depth is
  // off by at most the slab's density times half a slice, (2 / 0.51) / 32 / 2 = 0.061,
  // and the transmittance (T <= 1, d/dtau e^-tau >= -1) by no more.
  const OsmTexel offset(slab(0.26f, 0.77f, 2.0f, 10), 32);
  float worst = 0.0f;
  for (int i = 0; i <= 1000; ++i) {
    const float z = float(i) / 1000.0f;
    worst = std::max(worst, std::abs(offset.transmittance(z) - slab_truth(0.26f, 0.77f, 2.0f, z)));
  }
  std::printf("[ osm         ] slab between planes: worst %.4f\n", worst);
  EXPECT_LE(worst, 2.0f / 0.51f / 32.0f / 2.0f);
}

TEST(FourierOpacityMaps, ASmoothSlabIsClose) {
  const FomTexel fom(slab(0.2f, 0.8f, 1.0f, 12), 16);
  float worst = 0.0f;
  for (int i = 0; i <= 1000; ++i) {
    const float z = float(i) / 1000.0f;
    worst = std::max(worst, std::abs(fom.transmittance(z) - slab_truth(0.2f, 0.8f, 1.0f, z)));
  }
  std::printf("[ fom         ] slab tau 1, 16 terms: worst %.4f\n", worst);
  EXPECT_LE(worst, 0.05f);
}

// The known weakness: an opaque surface is a step the series cannot follow. With 16
// windowed terms it leaks light behind the step and dims in front of it (Gibbs
// ringing, damped by the window); measured away from the step by one period of the
// highest term (1/16), the damage stays within these bounds.
TEST(FourierOpacityMaps, RingingOnASharpStepStaysWithinItsBound) {
  const FomTexel fom({{0.5f, 0.5f, 0.0f}}, 16);
  float dimmed_in_front = 0.0f, lit_behind = 0.0f;
  for (int i = 0; i <= 1000; ++i) {
    const float z = float(i) / 1000.0f;
    if (z < 0.5f - 1.0f / 16.0f) dimmed_in_front = std::max(dimmed_in_front, 1.0f - fom.transmittance(z));
    if (z > 0.5f + 1.0f / 16.0f) lit_behind = std::max(lit_behind, fom.transmittance(z));
  }
  std::printf("[ fom         ] step: in front dimmed by up to %.4f, behind lit up to %.4f\n", dimmed_in_front, lit_behind);
  EXPECT_LE(dimmed_in_front, 0.1f);
  EXPECT_LE(lit_behind, 0.02f);
  // Without the window the ringing is worse: the window is doing its job.
  float raw_dimmed = 0.0f;
  for (int i = 0; i <= 1000; ++i) {
    const float z = float(i) / 1000.0f;
    if (z >= 0.5f - 1.0f / 16.0f) break;
    float optical_depth = 0.5f * fom.a[0] * z;
    for (int k = 1; k < 16; ++k) {
      const float w = 2.0f * OPACITY_PI * float(k);
      optical_depth += (fom.a[k] * std::sin(w * z) + fom.b[k] * (1.0f - std::cos(w * z))) / w;
    }
    raw_dimmed = std::max(raw_dimmed, 1.0f - opacity::fom_transmittance(optical_depth));
  }
  std::printf("[ fom         ] step without the window: in front dimmed by up to %.4f\n", raw_dimmed);
  EXPECT_GT(raw_dimmed, dimmed_in_front);
}

}  // namespace
}  // namespace techniques_test
}  // namespace avsm
