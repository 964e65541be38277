// The shared metallic-roughness BRDF (shaders/common/pbr_brdf.glsl, compiled as C++)
// against glTF 2.0's Appendix B written out independently here, and its sky term
// against the BRDF integrated numerically over a uniform sky.
#include <gtest/gtest.h>

#include <cmath>

#include "passes/camera/surfaces/pbr_brdf.h"

namespace avsm {
namespace pbr_brdf_test {  // one per file: test targets are unity builds
namespace {

constexpr double kPi = 3.14159265358979;

// f(l, v) for one channel, straight from the specification's formulas.
double appendix_b_brdf(double base, double metallic, double roughness, const glm::dvec3& n, const glm::dvec3& v,
                       const glm::dvec3& l) {
  const glm::dvec3 h = glm::normalize(l + v);
  const double nl = glm::dot(n, l), nv = glm::dot(n, v), nh = glm::dot(n, h), vh = glm::dot(v, h);
  const double alpha = roughness * roughness, a2 = alpha * alpha;
  const double d = a2 / (kPi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
  const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
  const double f0 = 0.04 + (base - 0.04) * metallic;
  const double f = f0 + (1.0 - f0) * std::pow(1.0 - vh, 5.0);
  return (1.0 - f) * base * (1.0 - metallic) / kPi + f * d * vis;
}

glm::dvec3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

TEST(PbrBrdf, MatchesTheSpecificationsFormulas) {
  const glm::dvec3 n(0, 1, 0);
  int compared = 0;
  for (double roughness : {0.1, 0.35, 0.7, 1.0})
    for (double metallic : {0.0, 0.5, 1.0})
      for (double view_theta : {0.1, 0.7, 1.3})
        for (double light_theta : {0.05, 0.6, 1.2, 1.5})
          for (double light_phi : {0.0, 1.0, 2.5, 3.1}) {
            const glm::dvec3 v = direction(view_theta, 0.0), l = direction(light_theta, light_phi);
            pbr::PbrSurface s{glm::vec3(0.9f, 0.5f, 0.1f), float(metallic), float(roughness)};
            const glm::vec3 got = pbr::pbr_brdf(s, glm::vec3(n), glm::vec3(v), glm::vec3(l));
            for (int c = 0; c < 3; ++c) {
              const double expected = appendix_b_brdf(s.base_color[c], metallic, roughness, n, v, l);
              ASSERT_NEAR(got[c], expected, 1e-3 * expected + 1e-6)  // float against double
                  << "roughness " << roughness << " metallic " << metallic << " view " << view_theta << " light "
                  << light_theta << "," << light_phi << " channel " << c;
            }
            ++compared;
          }
  EXPECT_EQ(compared, 4 * 3 * 3 * 4 * 4);
}

// A light's value is what a white Lambertian surface facing it reflects: pbr_direct of
// a rough, white, non-metallic surface lit and seen head-on is close to the light's
// value (the Fresnel term takes 4% from the diffuse and the specular gives some back).
TEST(PbrBrdf, DirectLightKeepsTheLambertCalibration) {
  const pbr::PbrSurface white{glm::vec3(1.0f), 0.0f, 1.0f};
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 head_on = pbr::pbr_direct(white, up, up, up, glm::vec3(1.0f));
  EXPECT_NEAR(head_on.x, 1.0f, 0.05f);
  const glm::vec3 l = glm::normalize(glm::vec3(1, 1, 0));  // 45 degrees: cosine falloff
  EXPECT_NEAR(pbr::pbr_direct(white, up, up, l, glm::vec3(1.0f)).x, head_on.x * std::sqrt(0.5f), 0.05f);
}

// With a black base colour the BRDF is specular only, so the sky term's specular part
// (Karis's fit) must follow the BRDF integrated over the hemisphere, within the fit's error.
TEST(PbrBrdf, SkySpecularMatchesTheIntegratedBrdf) {
  const glm::vec3 n(0, 1, 0);
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.3f, 0.6f, 1.0f})
      for (double view_theta : {0.2, 0.8, 1.2}) {
        // metallic 1 with a white base: F0 = 1; metallic 0 with a black base: F0 = 0.04, no diffuse.
        const pbr::PbrSurface s{glm::vec3(metallic), metallic, roughness};
        const glm::vec3 v = glm::vec3(direction(view_theta, 0.0));
        constexpr int kTheta = 400, kPhi = 400;
        double integral = 0.0;
        for (int i = 0; i < kTheta; ++i)
          for (int j = 0; j < kPhi; ++j) {
            const double theta = (i + 0.5) / kTheta * kPi / 2, phi = (j + 0.5) / kPhi * 2 * kPi;
            const glm::vec3 l = glm::vec3(direction(theta, phi));
            const double solid_angle = std::sin(theta) * (kPi / 2 / kTheta) * (2 * kPi / kPhi);
            integral += pbr::pbr_brdf(s, n, v, l).x * std::cos(theta) * solid_angle;
          }
        const float sky = pbr::pbr_sky(s, glm::dot(n, v), glm::vec3(1.0f), 1.0f).x;
        // Karis fitted Unreal's lookup table (a different visibility term), so the fit is
        // rough: measured within 0.03 of the integral for F0 = 0.04, 0.16 for F0 = 1.
        const double f0 = metallic > 0.5f ? 1.0 : 0.04;
        EXPECT_NEAR(sky, integral, 0.03 + 0.16 * f0)
            << "metallic " << metallic << " roughness " << roughness << " view " << view_theta;
      }
}

TEST(PbrBrdf, SkyDiffuseIsTheBaseColourTimesOcclusion) {
  const pbr::PbrSurface s{glm::vec3(0.5f, 0.2f, 0.8f), 0.25f, 1.0f};
  const glm::vec3 full = pbr::pbr_sky(s, 0.7f, glm::vec3(1.0f), 1.0f);
  const glm::vec3 half = pbr::pbr_sky(s, 0.7f, glm::vec3(1.0f), 0.5f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(half[c], 0.5f * full[c], 1e-6f);
  // The diffuse share differs between channels by base x (1 - metallic); the specular one by F0 only.
  const pbr::PbrSurface grey{glm::vec3(0.5f), 0.25f, 1.0f};
  const glm::vec3 grey_sky = pbr::pbr_sky(grey, 0.7f, glm::vec3(1.0f), 1.0f);
  EXPECT_GT(full.z, grey_sky.z);
  EXPECT_LT(full.y, grey_sky.y);
}

}  // namespace
}  // namespace pbr_brdf_test
}  // namespace avsm
