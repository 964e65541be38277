// Area lights with linearly transformed cosines (engine/lighting/ltc.h): the LTC integrals
// of rectangles, disks and spheres against Monte Carlo integrals of the engine's own BRDF
// over the same lights, the committed table against our fit, and bad tables.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "lighting/ltc.h"
#include "passes/camera/surfaces/pbr_brdf.h"

namespace avsm {
namespace ltc_test {  // one per file: test targets are unity builds
namespace {

using lighting::BrdfLobe;
using lighting::RectCorners;

constexpr double kPi = 3.14159265358979;
// Enough stratified samples that the reference's own error is far below the tolerances:
// 256^2 and 512^2 samples agree to 1e-3 of the integral on every light here, and Lambert's
// exact LTC integrals to 2e-5.
constexpr uint32_t kReferenceSamples = 512 * 512;
// Lambert is a clamped cosine, so its LTC integral is exact but for float rounding.
constexpr double kLambertTolerance = 1e-3;

float radians(float degrees) { return degrees * float(kPi) / 180.0f; }

// A shading point whose normal is not an axis (the shading frame is built, not assumed):
// local (x, y, z) with z the normal maps to world by `to_world`.
struct Shading {
  glm::mat3 to_world;
  glm::vec3 n, v;
};

Shading shading_point(float view_degrees) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.9f, -0.3f));
  const glm::vec3 t = glm::normalize(glm::cross(n, glm::vec3(0.0f, 0.0f, 1.0f)));
  const glm::mat3 to_world(t, glm::cross(n, t), n);
  const float theta = radians(view_degrees), azimuth = 0.7f;  // v off the tangent too
  const glm::vec3 v_local(std::sin(theta) * std::cos(azimuth), std::sin(theta) * std::sin(azimuth), std::cos(theta));
  return {to_world, n, to_world * v_local};
}

glm::vec3 direction(float elevation_degrees, float azimuth_degrees) {
  const float e = radians(elevation_degrees), a = radians(azimuth_degrees);
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

// A rectangle centred at `center` (local), facing the shading point but turned `tilt`
// degrees about its width axis; corners counter-clockwise seen from its lit side.
RectCorners rect_light(const glm::vec3& center, float width, float height, float tilt_degrees) {
  const glm::vec3 facing = -glm::normalize(center);
  const glm::vec3 across = glm::normalize(glm::cross(facing, glm::vec3(0.0f, 0.0f, 1.0f)));
  const glm::vec3 up = glm::cross(facing, across);
  const float tilt = radians(tilt_degrees);
  const glm::vec3 normal = std::cos(tilt) * facing + std::sin(tilt) * up;
  const glm::vec3 u = across * (0.5f * width), w = glm::cross(normal, across) * (0.5f * height);
  return {center - u - w, center + u - w, center + u + w, center - u + w};
}

RectCorners to_world(const Shading& s, const RectCorners& local) {
  RectCorners world;
  for (size_t i = 0; i < 4; ++i) world[i] = s.to_world * local[i];
  return world;
}

// Where the GGX tests put their lights: about the mirror direction, where the specular
// lobe is, but raised so that all of the light is above the horizon (the LTC, as the
// paper's, is not clipped to the surface's horizon, only to the cosine's).
struct Placement {
  const char* name;
  float distance, width, height, tilt_degrees, azimuth_offset, elevation_offset;
  bool small;  // a few degrees across: it sees the lobe at one spot, not on average
};
const Placement kPlacements[] = {
    {"large facing", 2.0f, 2.0f, 2.0f, 0.0f, 0.0f, 0.0f, false},
    {"small facing", 3.0f, 0.3f, 0.3f, 0.0f, 8.0f, 0.0f, true},
    {"large oblique", 2.0f, 2.5f, 1.5f, 50.0f, 20.0f, 0.0f, false},
    {"small oblique", 2.5f, 0.5f, 0.25f, 60.0f, -15.0f, 10.0f, true},
};

RectCorners place(const Placement& p, float view_degrees) {
  const float azimuth = 0.7f * 180.0f / float(kPi) + 180.0f + p.azimuth_offset;  // the mirror's
  const float angular_radius = std::atan(0.5f * std::hypot(p.width, p.height) / p.distance) * 180.0f / float(kPi);
  const float elevation = std::max(90.0f - view_degrees + p.elevation_offset, angular_radius + 5.0f);
  return rect_light(p.distance * direction(std::min(elevation, 89.0f), azimuth), p.width, p.height, p.tilt_degrees);
}

bool above_horizon(const RectCorners& local) {
  return std::all_of(local.begin(), local.end(), [](const glm::vec3& c) { return c.z > 0.0f; });
}

double relative_error(double got, double reference) { return std::abs(got - reference) / reference; }

// ---- Lambert: the clamped cosine's polygon integral -----------------------------------------

TEST(LtcPolygon, LambertRectanglesMatchMonteCarlo) {
  const Shading s = shading_point(0.0f);
  struct Case {
    const char* name;
    RectCorners local;
    bool two_sided;
  };
  const Case cases[] = {
      {"overhead, facing", rect_light({0.2f, 0.1f, 2.0f}, 1.5f, 1.0f, 0.0f), false},
      {"oblique, small", rect_light(2.5f * direction(35.0f, 40.0f), 0.3f, 0.2f, 55.0f), false},
      {"crossing the horizon", rect_light(2.0f * direction(8.0f, -30.0f), 3.0f, 2.0f, 20.0f), false},
      {"mostly below the horizon", rect_light(2.0f * direction(-20.0f, 100.0f), 2.0f, 2.0f, 0.0f), false},
      {"seen from behind, two-sided", rect_light(2.0f * direction(50.0f, 10.0f), 1.0f, 1.0f, 150.0f), true},
  };
  double max_error = 0.0;
  for (const Case& c : cases) {
    const RectCorners world = to_world(s, c.local);
    const double reference =
        lighting::mc_rect_integral(BrdfLobe::lambert, 1.0f, s.n, s.n, world, kReferenceSamples, 7, c.two_sided);
    const double ltc = lighting::ltc_lambert_rect(s.n, world, c.two_sided);
    ASSERT_GT(reference, 1e-4) << c.name;
    const double error = relative_error(ltc, reference);
    max_error = std::max(max_error, error);
    EXPECT_LT(error, kLambertTolerance) << c.name << ": LTC " << ltc << ", Monte Carlo " << reference;
    // The generic polygon path (any number of corners) gives what the shader's quad path does.
    const std::vector<glm::vec3> polygon(world.begin(), world.end());
    EXPECT_NEAR(lighting::ltc_polygon_integral(lighting::ltc_lambert_lobe(s.n, s.v), polygon, c.two_sided), ltc, 1e-6)
        << c.name;
  }
  std::printf("Lambert rectangles: max relative error against Monte Carlo %.2e\n", max_error);
  // A one-sided light seen from behind sends nothing.
  const RectCorners behind = to_world(s, rect_light(2.0f * direction(50.0f, 10.0f), 1.0f, 1.0f, 150.0f));
  EXPECT_EQ(lighting::ltc_lambert_rect(s.n, behind, false), 0.0f);
  EXPECT_EQ(lighting::mc_rect_integral(BrdfLobe::lambert, 1.0f, s.n, s.n, behind, 1024, 7), 0.0f);
}

// The clamped cosine's integral over polygons in its own space: the whole upper hemisphere
// is 1, a polygon wholly below the horizon 0, and one the horizon cuts counts its upper part.
TEST(LtcPolygon, ClampedCosineIntegralOfKnownPolygons) {
  // A huge square overhead, lit side down: all of the hemisphere but a rim of 1e-4 radians.
  const float side = 1e4f;
  const std::vector<glm::vec3> overhead{{side, side, 1}, {side, -side, 1}, {-side, -side, 1}, {-side, side, 1}};
  EXPECT_NEAR(lighting::clamped_cosine_polygon_integral(overhead), 1.0, 1e-3);
  // Its corners the other way round: its unlit side faces the origin.
  const std::vector<glm::vec3> reversed(overhead.rbegin(), overhead.rend());
  EXPECT_NEAR(lighting::clamped_cosine_polygon_integral(reversed), -1.0, 1e-3);
  // The same square below the horizon.
  std::vector<glm::vec3> below = overhead;
  for (glm::vec3& p : below) p.z = -1.0f;
  EXPECT_EQ(lighting::clamped_cosine_polygon_integral(below), 0.0f);
  // A huge wall at y = 1 from far below the horizon to far above covers the directions
  // with y > 0; clipped to the upper hemisphere, that is half of the cosine's integral.
  const std::vector<glm::vec3> wall{{side, 1, side}, {-side, 1, side}, {-side, 1, -side}, {side, 1, -side}};
  EXPECT_NEAR(lighting::clamped_cosine_polygon_integral(wall), 0.5, 1e-3);
  // A triangle with one corner below the horizon: the clipped quadrilateral's integral,
  // against the same quadrilateral given directly (its corners where the edges cross z = 0).
  const glm::vec3 a(1.0f, 0.5f, 1.0f), b(-1.0f, 0.8f, 1.5f), c(0.2f, -0.5f, -1.0f);
  const auto crossing = [](const glm::vec3& p, const glm::vec3& q) { return p + (q - p) * (p.z / (p.z - q.z)); };
  const std::vector<glm::vec3> triangle{a, b, c}, clipped{a, b, crossing(b, c), crossing(c, a)};
  EXPECT_NE(lighting::clamped_cosine_polygon_integral(triangle), 0.0f);
  EXPECT_NEAR(lighting::clamped_cosine_polygon_integral(triangle), lighting::clamped_cosine_polygon_integral(clipped),
              1e-6);
}

TEST(LtcPolygon, LambertDiskAndSphereMatchMonteCarlo) {
  const Shading s = shading_point(0.0f);
  const lighting::LtcLobe lobe = lighting::ltc_lambert_lobe(s.n, s.v);
  double max_error = 0.0;
  // Disks: overhead, and one the horizon cuts (the generic polygon clipping).
  for (const auto& [center_local, normal_local] :
       {std::pair{glm::vec3(0.3f, 0.0f, 1.5f), glm::vec3(0.0f, 0.2f, -1.0f)},
        std::pair{glm::vec3(1.5f, 0.5f, 0.2f), glm::vec3(-1.0f, 0.0f, 0.1f)}}) {
    const glm::vec3 center = s.to_world * center_local, normal = s.to_world * normal_local;
    const double reference =
        lighting::mc_disk_integral(BrdfLobe::lambert, 1.0f, s.n, s.v, center, normal, 0.8f, kReferenceSamples, 3);
    const double ltc = lighting::ltc_disk_integral(lobe, center, normal, 0.8f, false);
    const double error = relative_error(ltc, reference);
    max_error = std::max(max_error, error);
    // The disk is a 64-gon of the same area: its shape differs slightly from the circle's.
    EXPECT_LT(error, 2e-3) << "disk at " << center_local.x << "," << center_local.y << "," << center_local.z;
  }
  // A sphere well above, one the horizon cuts, and one around the shading point.
  for (const auto& [center_local, radius] :
       {std::pair{glm::vec3(0.5f, 0.3f, 2.0f), 0.7f}, std::pair{glm::vec3(-1.0f, 1.5f, 0.3f), 0.8f},
        std::pair{glm::vec3(0.1f, 0.0f, 0.1f), 1.0f}}) {
    const glm::vec3 center = s.to_world * center_local;
    const double reference =
        lighting::mc_sphere_integral(BrdfLobe::lambert, 1.0f, s.n, s.v, center, radius, kReferenceSamples, 5);
    const double ltc = lighting::ltc_sphere_integral(lobe, center, radius);
    const double error = relative_error(ltc, reference);
    max_error = std::max(max_error, error);
    EXPECT_LT(error, 2e-3) << "sphere at " << center_local.x << "," << center_local.y << "," << center_local.z;
  }
  std::printf("Lambert disks and spheres: max relative error against Monte Carlo %.2e\n", max_error);
}

// ---- GGX: the fitted table -----------------------------------------------------------------

// Bounds on the GGX LTC's error relative to the exact integral. The brief's 2% holds for
// views up to 30 degrees off the normal, but for small lights on the roughest surfaces.
// Elsewhere a single LTC cannot follow GGX (engine/lighting/ltc.h, "Accuracy"), and each
// bound is the worst case measured with the committed table, with a margin, so that a
// worse fit still fails. Measured (max over roughness 0.3, 0.5, 0.8 and 1 and the lights):
//   up to 30 degrees: 1.5%, but 3.5% for the small lights at roughness 0.8 and 1 head on
//     (GGX with alpha near 1 is shaped as cos / (1 + cos), which no scaled cosine is);
//   60 degrees: 6.3% for the large lights, 16.1% for the small (roughness 0.3, off-peak);
//   75 degrees: 16.7% for the large lights, 52.8% for the small (roughness 0.3, off-peak:
//     GGX's long tail, where the clamped cosine has half its density).
double ggx_error_bound(float roughness, float view_degrees, bool small_light) {
  if (view_degrees <= 30.0f) return (small_light && roughness > 0.5f) ? 0.04 : 0.02;
  if (view_degrees <= 60.0f) return small_light ? 0.18 : 0.07;
  return small_light ? 0.56 : 0.18;
}

TEST(LtcGgx, RectanglesMatchMonteCarlo) {
  const lighting::LtcTable& table = lighting::builtin_ggx_table();
  const float kViews[] = {0.0f, 30.0f, 60.0f, 75.0f};
  std::printf(
      "GGX rectangles, LTC against Monte Carlo, signed relative error in %%, per view angle:\n"
      "  lights: large facing, small facing, large oblique, small oblique\n");
  for (float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
    std::string line;
    std::map<bool, double> max_error;  // by light size
    double sum = 0.0;
    int count = 0;
    for (float view_degrees : kViews) {
      char heading[32];
      std::snprintf(heading, sizeof heading, "  %2.0f deg:", view_degrees);
      line += heading;
      for (const Placement& placement : kPlacements) {
        const Shading s = shading_point(view_degrees);
        const RectCorners local = place(placement, view_degrees);
        ASSERT_TRUE(above_horizon(local)) << placement.name << " at view " << view_degrees;
        const RectCorners world = to_world(s, local);
        const double reference =
            lighting::mc_rect_integral(BrdfLobe::ggx_specular, roughness, s.n, s.v, world, kReferenceSamples, 11);
        const double ltc = lighting::ltc_rect_integral(table, roughness, s.n, s.v, world, false);
        const double error = relative_error(ltc, reference);
        EXPECT_LT(error, ggx_error_bound(roughness, view_degrees, placement.small))
            << "roughness " << roughness << ", view " << view_degrees << " degrees, " << placement.name << ": LTC "
            << ltc << ", Monte Carlo " << reference;
        char cell[16];
        std::snprintf(cell, sizeof cell, " %+6.1f", 100.0 * (ltc - reference) / reference);
        line += cell;
        max_error[placement.small] = std::max(max_error[placement.small], error);
        sum += error;
        ++count;
      }
    }
    std::printf("roughness %.1f:%s\n  max %.4f (large lights %.4f, small %.4f), mean %.4f\n", roughness, line.c_str(),
                std::max(max_error[false], max_error[true]), max_error[false], max_error[true], sum / count);
  }
}

TEST(LtcGgx, DisksAndSpheresMatchMonteCarlo) {
  const lighting::LtcTable& table = lighting::builtin_ggx_table();
  double max_error = 0.0;
  for (float roughness : {0.3f, 0.6f, 1.0f})
    for (float view_degrees : {20.0f, 55.0f}) {
      const Shading s = shading_point(view_degrees);
      const lighting::LtcLobe lobe = lighting::ltc_ggx_lobe(table, roughness, s.n, s.v);
      const glm::vec3 mirror = glm::reflect(-s.v, s.n);
      const glm::vec3 disk_center = 2.0f * glm::normalize(mirror + 0.4f * s.n), disk_normal = -disk_center;
      const double disk_reference = lighting::mc_disk_integral(BrdfLobe::ggx_specular, roughness, s.n, s.v, disk_center,
                                                               disk_normal, 0.6f, kReferenceSamples, 13);
      const double disk = lighting::ltc_disk_integral(lobe, disk_center, disk_normal, 0.6f, false);
      const glm::vec3 sphere_center = 3.0f * glm::normalize(mirror + 0.2f * s.n);
      const double sphere_reference = lighting::mc_sphere_integral(BrdfLobe::ggx_specular, roughness, s.n, s.v,
                                                                   sphere_center, 0.5f, kReferenceSamples, 17);
      const double sphere = lighting::ltc_sphere_integral(lobe, sphere_center, 0.5f);
      for (const auto& [name, got, reference] :
           {std::tuple{"disk", disk, disk_reference}, std::tuple{"sphere", sphere, sphere_reference}}) {
        const double error = relative_error(got, reference);
        max_error = std::max(max_error, error);
        EXPECT_LT(error, ggx_error_bound(roughness, view_degrees, true))
            << name << " at roughness " << roughness << ", view " << view_degrees << ": LTC " << got << ", Monte Carlo "
            << reference;
      }
    }
  std::printf("GGX disks and spheres: max relative error against Monte Carlo %.4f\n", max_error);
}

// norm is the engine's GGX lobe integrated over all directions (a sphere around the point
// is every direction), and with (norm, fresnel) Schlick's Fresnel comes out as documented:
// the integral of the engine's specular BRDF x cos for F0 is F0 norm + (1 - F0) fresnel.
TEST(LtcGgx, MagnitudesAreTheEnginesDirectionalAlbedo) {
  const lighting::LtcTable& table = lighting::builtin_ggx_table();
  for (uint32_t row : {table.size * 3 / 10, table.size * 6 / 10, table.size - 1})
    for (uint32_t column : {0u, table.size / 2, table.size - 3}) {
      const float roughness = lighting::ltc_row_roughness(table.size, row);
      const float cos_theta = lighting::ltc_column_cos_theta(table.size, column);
      const glm::vec3 n(0.0f, 0.0f, 1.0f), v(std::sqrt(1.0f - cos_theta * cos_theta), 0.0f, cos_theta);
      const lighting::LtcEntry entry = lighting::ltc_table_entry(table, row, column);
      const double norm =
          lighting::mc_sphere_integral(BrdfLobe::ggx_specular, roughness, n, v, glm::vec3(0.0f), 1.0f, 1024 * 1024, 19);
      EXPECT_NEAR(entry.magnitude.x, norm, 2e-3 * norm) << "row " << row << ", column " << column;
      for (float f0 : {0.04f, 0.5f}) {
        // Specular only: metal whose base colour is F0.
        const pbr::PbrSurface metal{glm::vec3(f0), 1.0f, roughness};
        constexpr int kSide = 768;
        double integral = 0.0;
        for (int i = 0; i < kSide; ++i)
          for (int j = 0; j < kSide; ++j) {  // uniform over the hemisphere's area: z = cos theta uniform
            const float z = (i + 0.5f) / kSide, phi = 2.0f * float(kPi) * (j + 0.5f) / kSide;
            const float r = std::sqrt(1.0f - z * z);
            const glm::vec3 l(r * std::cos(phi), r * std::sin(phi), z);
            integral += pbr::pbr_brdf(metal, n, v, l).x * z;
          }
        integral *= 2.0 * kPi / (double(kSide) * kSide);
        const float magnitude = lighting::ltc_specular_magnitude(entry, f0);
        EXPECT_NEAR(magnitude, integral, 5e-3 * integral) << "row " << row << ", column " << column << ", F0 " << f0;
      }
    }
}

// ---- The committed table -------------------------------------------------------------------

// The compiled-in table is our fit's output: entries across the table fitted again (each
// from the neighbour the whole fit started it from) come back the same, and writing the
// table out with the arguments its header names gives the committed file byte for byte.
TEST(LtcTable, BuiltinTableIsOurFitsOutput) {
  const lighting::LtcTable& table = lighting::builtin_ggx_table();
  ASSERT_EQ(table.size, lighting::kLtcDefaultTableSize);
  const uint32_t last = table.size - 1;
  for (const auto& [row, column] : {std::pair{last, 0u}, std::pair{20u, 0u}, std::pair{19u, 14u}, std::pair{32u, 40u},
                                    std::pair{50u, last}, std::pair{4u, 24u}}) {
    float fit_error = -1.0f;
    const lighting::LtcEntry refit = lighting::refit_ggx_entry(table, row, column, &fit_error);
    const lighting::LtcEntry stored = lighting::ltc_table_entry(table, row, column);
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(refit.inverse_matrix[k], stored.inverse_matrix[k],
                  1e-5f * (1.0f + std::abs(stored.inverse_matrix[k])))
          << "row " << row << ", column " << column << ", coefficient " << k;
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(refit.magnitude[k], stored.magnitude[k], 1e-6f) << "row " << row << ", column " << column;
    EXPECT_GE(fit_error, 0.0f);
  }

  std::ifstream committed_file(AVSM_LTC_TABLE_SOURCE, std::ios::binary);
  ASSERT_TRUE(committed_file) << AVSM_LTC_TABLE_SOURCE;
  const std::string committed{std::istreambuf_iterator<char>(committed_file), std::istreambuf_iterator<char>()};
  const std::string marker = "// Arguments: ";
  const size_t begin = committed.find(marker);
  ASSERT_NE(begin, std::string::npos);
  const std::string arguments =
      committed.substr(begin + marker.size(), committed.find('\n', begin) - begin - marker.size());
  EXPECT_EQ(arguments.rfind("avsm-ltc-fit ", 0), 0u) << arguments;
  const std::filesystem::path written = std::filesystem::path(::testing::TempDir()) / "ltc_ggx_table_again.inc";
  lighting::write_table_source(table, written, arguments);
  std::ifstream written_file(written, std::ios::binary);
  const std::string again{std::istreambuf_iterator<char>(written_file), std::istreambuf_iterator<char>()};
  EXPECT_TRUE(again == committed) << "the committed table is not what write_table_source makes of it";
}

// Entries sit where the shader's texture coordinates put them: a lookup at an entry's own
// roughness and view angle gives that entry.
TEST(LtcTable, LookupAtAnEntryGivesTheEntry) {
  EXPECT_EQ(lighting::kLtcMinRoughness, pbr::kPbrMinRoughness);
  const lighting::LtcTable& table = lighting::builtin_ggx_table();
  for (uint32_t row : {0u, 13u, table.size - 1})
    for (uint32_t column : {0u, 5u, table.size - 1}) {
      const lighting::LtcEntry looked_up = lighting::ltc_lookup(table, lighting::ltc_row_roughness(table.size, row),
                                                                lighting::ltc_column_cos_theta(table.size, column));
      const lighting::LtcEntry stored = lighting::ltc_table_entry(table, row, column);
      for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(looked_up.inverse_matrix[k], stored.inverse_matrix[k],
                    1e-4f * (1.0f + std::abs(stored.inverse_matrix[k])))
            << "row " << row << ", column " << column;
      EXPECT_NEAR(looked_up.magnitude.x, stored.magnitude.x, 1e-5f);
    }
}

TEST(LtcTable, BadSizesAreErrors) {
  for (uint32_t size : {0u, 1u, lighting::kLtcMaxTableSize + 1}) {
    try {
      (void)lighting::fit_ggx_table(size);
      ADD_FAILURE() << "size " << size << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("LTC table size " + std::to_string(size)), std::string::npos) << e.what();
    }
  }
  lighting::LtcTable short_of_entries = lighting::builtin_ggx_table();
  short_of_entries.magnitude.pop_back();
  EXPECT_THROW((void)lighting::ltc_lookup(short_of_entries, 0.5f, 0.5f), std::invalid_argument);
  EXPECT_THROW(
      lighting::write_table_source(short_of_entries, std::filesystem::path(::testing::TempDir()) / "bad.inc", "x"),
      std::invalid_argument);
  lighting::LtcTable one_entry{1, {glm::vec4(1, 0, 0, 1)}, {glm::vec2(1, 0)}};
  EXPECT_THROW((void)lighting::ltc_lookup(one_entry, 0.5f, 0.5f), std::invalid_argument);
  EXPECT_THROW((void)lighting::refit_ggx_entry(lighting::builtin_ggx_table(), lighting::kLtcDefaultTableSize, 0),
               std::invalid_argument);
}

}  // namespace
}  // namespace ltc_test
}  // namespace avsm
