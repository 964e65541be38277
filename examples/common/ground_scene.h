#pragma once
// The host examples' scene and checks (examples/host_embed, host_raw): a ground quad, a
// box hovering over it and two sheets of hair strands as CPU arrays in the layouts the
// engine's caster views document, and what the geometry predicts of the shadows on the
// ground (the transmittance the shading pass keeps in the image's alpha).
#include <avsm/shadows.h>
#include "gpu/transfer.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace host {

// The scene, in world units, y up. The light travels along (1, -2, 0): a point at height h
// casts its shadow h / 2 further along +x.

constexpr float kGroundHalf = 3.0f;                      // ground: x, z in [-3, 3], y = 0
constexpr glm::vec3 kBoxMin{-0.5f, 1.0f, -0.5f};          // the blocker
constexpr glm::vec3 kBoxMax{0.5f, 2.0f, 0.5f};
inline const glm::vec3 kLightTravel = glm::normalize(glm::vec3(1.0f, -2.0f, 0.0f));
// Hair: two sheets of strands along z, 0.1 apart in height, over x in [-2.6, -1.4],
// z in [-2.6, -1.4]; each strand is 40% opaque and a third of its spacing wide.
constexpr float kHairHeight = 1.5f;
constexpr float kHairMinX = -2.6f, kHairMaxX = -1.4f, kHairMinZ = -2.6f, kHairMaxZ = -1.4f;

// --point-light: a point light up and to the -x side, whose rays cross the box at about
// the sun's slant, so the same checks hold with its own projection.
inline const glm::vec3 kPointLight{-4.0f, 8.0f, 0.0f};
inline bool g_point_light = false;

// Where a point at (x, height) in the plane z = 0 lands on the ground along the light.
inline float ground_landing(float x, float height) {
  if (g_point_light) return kPointLight.x + (x - kPointLight.x) * kPointLight.y / (kPointLight.y - height);
  return x - kLightTravel.x / kLightTravel.y * height;
}

// ---------------------------------------------------------------------------------------
// The casters as CPU arrays: the host uploads them its own way.

struct CasterArrays {
  std::vector<avsm::CasterVertex> vertices;  // ground + box
  std::vector<uint32_t> indices;
  std::vector<avsm::MeshDraw> draws;
  std::vector<glm::vec4> strand_points;
  std::vector<avsm::StrandSegment> strand_segments;
  std::vector<avsm::StrandParameters> strands;
  avsm::Bounds bounds;
};

inline void add_quad(std::vector<avsm::CasterVertex>& vertices, std::vector<uint32_t>& indices, const glm::vec3 corners[4],
              const glm::vec3& normal) {
  const uint32_t base = uint32_t(vertices.size());
  for (int i = 0; i < 4; ++i)
    vertices.push_back({{corners[i].x, corners[i].y, corners[i].z}, {normal.x, normal.y, normal.z}, {0.0f, 0.0f}});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
}

inline void add_box(std::vector<avsm::CasterVertex>& vertices, std::vector<uint32_t>& indices, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 faces[6][4] = {
      {{lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}},  // -x
      {{hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}},  // +x
      {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}},  // -y
      {{lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}},  // +y
      {{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z}},  // -z
      {{lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}},  // +z
  };
  const glm::vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int f = 0; f < 6; ++f) add_quad(vertices, indices, faces[f], normals[f]);
}

inline CasterArrays make_casters() {
  CasterArrays c;
  const glm::vec3 ground[4] = {{-kGroundHalf, 0, -kGroundHalf}, {-kGroundHalf, 0, kGroundHalf},
                               {kGroundHalf, 0, kGroundHalf}, {kGroundHalf, 0, -kGroundHalf}};
  add_quad(c.vertices, c.indices, ground, {0, 1, 0});
  add_box(c.vertices, c.indices, kBoxMin, kBoxMax);
  for (const avsm::CasterVertex& v : c.vertices) c.bounds.extend(glm::vec3(v.position[0], v.position[1], v.position[2]));
  // One draw for the ground, one for the box: the view takes any number of ranges.
  c.draws = {{0, 6, 0}, {6, uint32_t(c.indices.size()) - 6, 0}};

  // Hair: straight strands along z, 4 segments each, in two sheets.
  constexpr float kSpacing = 0.03f;
  for (int sheet = 0; sheet < 2; ++sheet) {
    const float y = kHairHeight + 0.1f * float(sheet);
    for (float x = kHairMinX + 0.5f * kSpacing; x < kHairMaxX; x += kSpacing) {
      const uint32_t strand = uint32_t(c.strands.size());
      c.strands.push_back({{0.4f, 0.3f, 0.2f, /*opacity=*/0.4f}, /*width=*/kSpacing / 3.0f, {}});
      for (int p = 0; p <= 4; ++p) {
        if (p < 4) c.strand_segments.push_back({uint32_t(c.strand_points.size()), strand});
        const glm::vec3 point(x, y, kHairMinZ + (kHairMaxZ - kHairMinZ) * float(p) / 4.0f);
        c.strand_points.emplace_back(point, 1.0f);
        c.bounds.extend(point);
      }
    }
  }
  return c;
}

// ---------------------------------------------------------------------------------------
// Reading the result: transmittance at world points, and the shadow's extent along x.

// The picture without the transmittance the shading pass kept in alpha.
inline avsm::gpu::ImageRGBA32F opaque(avsm::gpu::ImageRGBA32F image) {
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
  return image;
}

// The transmittance the shading pass stored (alpha) at the pixel over ground point (x, z).
inline float transmittance_at(const avsm::gpu::ImageRGBA32F& image, float x, float z) {
  const auto pixel = [&](float world, uint32_t size) {
    const float u = (world + kGroundHalf) / (2 * kGroundHalf);
    return uint32_t(std::clamp(int(u * float(size)), 0, int(size) - 1));
  };
  return image.at(pixel(x, image.width), pixel(z, image.height))[3];
}

// Along the row z, the first and last ground x whose transmittance is below one half.
inline std::optional<std::pair<float, float>> shadow_extent_along_x(const avsm::gpu::ImageRGBA32F& image, float z) {
  std::optional<std::pair<float, float>> extent;
  const uint32_t row = uint32_t((z + kGroundHalf) / (2 * kGroundHalf) * float(image.height));
  for (uint32_t x = 0; x < image.width; ++x) {
    if (image.at(x, row)[3] >= 0.5f) continue;
    const float world = -kGroundHalf + (float(x) + 0.5f) / float(image.width) * 2 * kGroundHalf;
    if (!extent) extent = std::pair{world, world};
    extent->second = world;
  }
  return extent;
}

struct Checker {
  int failures = 0;
  void expect(bool ok, const std::string& what) {
    std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
    if (!ok) ++failures;
  }
};

// What the geometry predicts: under the box's shadow (shifted along x by h / 2 for a
// point at height h) nothing gets through; beside it, and right under the box where
// the slanted light passes, everything does; the hair lets part of it through.
inline int check_against_geometry(const avsm::gpu::ImageRGBA32F& image) {
  Checker c;
  const float shadow_begin = ground_landing(kBoxMin.x, kBoxMin.y);  // the box's lower -x edge
  const float shadow_end = ground_landing(kBoxMax.x, kBoxMax.y);    // its upper +x edge
  const float in_shadow = transmittance_at(image, 0.5f * (shadow_begin + shadow_end), 0.0f);
  const float beside = transmittance_at(image, shadow_end + 0.8f, 0.0f);
  const float under_box = transmittance_at(image, kBoxMin.x + 0.2f, 0.0f);  // the light passes under the box here
  const float hair_x = ground_landing(0.5f * (kHairMinX + kHairMaxX), kHairHeight + 0.05f);
  const float under_hair = transmittance_at(image, hair_x, 0.5f * (kHairMinZ + kHairMaxZ));
  char line[160];
  std::snprintf(line, sizeof(line), "box shadow at x=%.2f: T=%.3f (expected < 0.1)", 0.5f * (shadow_begin + shadow_end), in_shadow);
  c.expect(in_shadow < 0.1f, line);
  std::snprintf(line, sizeof(line), "beside the shadow at x=%.2f: T=%.3f (expected > 0.9)", shadow_end + 0.8f, beside);
  c.expect(beside > 0.9f, line);
  std::snprintf(line, sizeof(line), "right under the box at x=%.2f: T=%.3f (expected > 0.9: the light is slanted)",
                kBoxMin.x + 0.2f, under_box);
  c.expect(under_box > 0.9f, line);
  std::snprintf(line, sizeof(line), "hair shadow at x=%.2f: T=%.3f (expected partial, 0.15 .. 0.85)", hair_x, under_hair);
  c.expect(under_hair > 0.15f && under_hair < 0.85f, line);
  std::snprintf(line, sizeof(line), "lit pixel much brighter than the shadowed one: %.3f vs %.3f", beside, in_shadow);
  c.expect(beside > 5.0f * std::max(in_shadow, 0.01f), line);

  // The shadow's edges along z = 0: within a map texel and a pixel or two of the prediction.
  constexpr float kTolerance = 0.15f;
  const auto extent = shadow_extent_along_x(image, 0.0f);
  if (!extent) {
    c.expect(false, "a shadow along z = 0");
  } else {
    std::snprintf(line, sizeof(line), "shadow along z = 0 spans x = %.3f .. %.3f (predicted %.3f .. %.3f)", extent->first,
                  extent->second, shadow_begin, shadow_end);
    c.expect(std::abs(extent->first - shadow_begin) < kTolerance && std::abs(extent->second - shadow_end) < kTolerance, line);
  }
  return c.failures;
}

}  // namespace host
