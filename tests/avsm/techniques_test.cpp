// The comparison techniques' math on the CPU (shaders/techniques/*.glsl compiled as
// C++): deep shadow map compression against its error threshold, opacity shadow maps
// and Fourier opacity maps against slabs and a sharp step with known transmittance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "passes/deep_shadow.h"
#include "passes/opacity_maps.h"

namespace avsm {
namespace {

using core::AvsmCurve;

constexpr float kFar = 100.0f;

// ---- Deep shadow maps ----

AvsmCurve random_exact_curve(std::mt19937& rng) {
  // Up to 7 segments: the 18-node curve then holds them exactly (2 nodes each + far).
  std::uniform_int_distribution<int> count(1, 7);
  std::uniform_real_distribution<float> depth(1.0f, 90.0f), length(0.0f, 8.0f), trans(0.0f, 1.0f);
  AvsmCurve c = core::avsm_clear(kFar);
  for (int i = count(rng); i > 0; --i) {
    const float entry = depth(rng);
    core::avsm_insert_segment(c, entry, entry + length(rng), trans(rng), 16);
  }
  return c;
}

float max_difference(const AvsmCurve& a, const AvsmCurve& b) {
  float worst = 0.0f;
  for (int i = 0; i <= 4000; ++i) {
    const float d = kFar * 1.02f * float(i) / 4000.0f;
    worst = std::max(worst, std::abs(core::avsm_evaluate_linear(a, d) - core::avsm_evaluate_linear(b, d)));
  }
  return worst;
}

TEST(DeepShadowMaps, CompressionStaysWithinItsErrorThreshold) {
  std::mt19937 rng(7);
  for (float error : {0.002f, 0.01f, 0.05f, 0.2f}) {
    int exact_nodes = 0, kept_nodes = 0;
    float worst = 0.0f;
    for (int trial = 0; trial < 400; ++trial) {
      const AvsmCurve exact = random_exact_curve(rng);
      AvsmCurve compressed;
      core::dsm_compress(exact, error, compressed);
      ASSERT_LE(compressed.count, exact.count);
      worst = std::max(worst, max_difference(exact, compressed));
      exact_nodes += exact.count;
      kept_nodes += compressed.count;
    }
    std::printf("[ dsm         ] error %.3f: worst %.5f, nodes kept %d of %d\n", error, worst, kept_nodes, exact_nodes);
    EXPECT_LE(worst, error + 1e-5f) << "error threshold " << error;
    if (error >= 0.05f) {
      EXPECT_LT(kept_nodes, exact_nodes) << "a loose threshold must drop nodes";
    }
  }
}

TEST(DeepShadowMaps, AnOpaqueStepStaysSharp) {
  AvsmCurve exact = core::avsm_clear(kFar);
  core::avsm_insert_segment(exact, 50.0f, 50.0f, 0.0f, 16);  // an opaque surface: a step at depth 50
  AvsmCurve compressed;
  core::dsm_compress(exact, 0.01f, compressed);
  EXPECT_NEAR(core::avsm_evaluate_linear(compressed, 49.999f), 1.0f, 1e-6f);
  EXPECT_NEAR(core::avsm_evaluate_linear(compressed, 50.001f), 0.0f, 1e-6f);
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
}  // namespace avsm
