// Procedural smoke plume written with OpenVDB.
#include "content.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace avsm::content {

float hash01(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::uint32_t h = a * 0x8da6b343u ^ b * 0xd8163841u ^ c * 0xcb1ab31fu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

namespace {

constexpr float kVoxelSize = 0.025f;   // metres
constexpr int kHalfWidth = 48;         // voxels either side of the axis in X and Z
constexpr int kHeight = 128;           // voxels up
constexpr float kHeightMetres = kHeight * kVoxelSize;

float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Value noise on an integer lattice, smoothly interpolated; in [0, 1).
float value_noise(float x, float y, float z, std::uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const auto ix = std::uint32_t(std::int32_t(fx)), iy = std::uint32_t(std::int32_t(fy)), iz = std::uint32_t(std::int32_t(fz));
  const float tx = smoothstep(0, 1, x - fx), ty = smoothstep(0, 1, y - fy), tz = smoothstep(0, 1, z - fz);
  auto corner = [&](std::uint32_t dx, std::uint32_t dy, std::uint32_t dz) {
    return hash01(ix + dx + seed * 7919u, iy + dy, iz + dz);
  };
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  const float x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), tx), x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), tx);
  const float x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), tx), x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), tx);
  return lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz);
}

float fbm(float x, float y, float z) {
  float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
  for (std::uint32_t octave = 0; octave < 4; ++octave) {
    sum += amplitude * value_noise(x, y, z, octave);
    norm += amplitude;
    x *= 2.03f, y *= 2.03f, z *= 2.03f;
    amplitude *= 0.5f;
  }
  return sum / norm;
}

// Density at a point in metres (plume base at the origin).
float plume_density(float x, float y, float z) {
  const float h = y / kHeightMetres;  // 0 at the base, 1 at the top
  // The axis drifts a little with height, as if in a light breeze.
  const float axis_x = 0.18f * h * h + 0.05f * std::sin(6.0f * h);
  const float axis_z = -0.08f * h;
  const float radius = 0.2f + 0.8f * h;
  const float r = std::hypot(x - axis_x, z - axis_z) / radius;
  const float profile = 1.0f - smoothstep(0.35f, 1.0f, r);
  if (profile <= 0.0f) return 0.0f;
  const float billow = fbm(x * 2.6f, y * 2.0f - 1.3f * h, z * 2.6f);
  const float shaped = std::max(0.0f, billow * 1.9f - 0.55f);
  const float fade = smoothstep(0.0f, 0.06f, h) * (1.0f - smoothstep(0.7f, 1.0f, h));
  return 4.0f * (1.0f - 0.55f * h) * profile * shaped * fade;
}

}  // namespace

// OpenVDB stamps every file with a random UUID; overwrite it with a fixed one
// so that the build writes byte-identical content every time. The UUID is
// 36 ASCII characters after the magic (8 bytes), file version, library major
// and minor (4 bytes each) and the "has grid offsets" flag (1 byte).
void make_uuid_deterministic(const std::filesystem::path& file) {
  constexpr std::streamoff kUuidOffset = 8 + 4 + 4 + 4 + 1;
  constexpr char kFixedUuid[] = "a75bd1f0-0000-4000-8000-000000000001";
  std::fstream stream(file, std::ios::in | std::ios::out | std::ios::binary);
  char current[36];
  stream.seekg(kUuidOffset);
  if (!stream.read(current, 36) || current[8] != '-' || current[13] != '-')
    throw std::runtime_error(file.string() + ": unexpected OpenVDB header layout, cannot fix its UUID");
  stream.seekp(kUuidOffset);
  stream.write(kFixedUuid, 36);
  if (!stream) throw std::runtime_error(file.string() + ": cannot rewrite the UUID");
}

void write_plume_vdb(const std::filesystem::path& file) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(kVoxelSize));
  auto accessor = grid->getAccessor();
  for (int k = -kHalfWidth; k < kHalfWidth; ++k)
    for (int j = 0; j < kHeight; ++j)
      for (int i = -kHalfWidth; i < kHalfWidth; ++i) {
        const float density = plume_density(i * kVoxelSize, j * kVoxelSize, k * kVoxelSize);
        if (density > 1e-3f) accessor.setValue(openvdb::Coord(i, j, k), density);
      }
  openvdb::io::File vdb(file.string());
  vdb.write({grid});
  vdb.close();
  make_uuid_deterministic(file);
}

}  // namespace avsm::content
