// A short simulated smoke sequence written with OpenVDB, one file per frame, as fluid
// caches arrive (Houdini, EmberGen, Blender's Mantaflow): a buoyant plume carried by a
// swirling wind. Semi-Lagrangian advection (Stam, "Stable Fluids", 1999) on a dense grid:
// no pressure solve, since only the look of moving smoke matters here.
#include "content.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace avsm::content {
namespace {

constexpr float kVoxel = 0.03f;                  // metres
constexpr int kSizeX = 48, kSizeY = 80, kSizeZ = 48;  // voxels: 1.44 x 2.4 x 1.44 m, base at y = 0
constexpr float kStep = 1.0f / 24.0f;            // seconds per frame
constexpr int kPreRollFrames = 14;               // simulated before frame 1, so it starts as a plume

struct Field {
  std::vector<float> values = std::vector<float>(std::size_t(kSizeX) * kSizeY * kSizeZ, 0.0f);
  float& at(int x, int y, int z) { return values[std::size_t(x) + std::size_t(kSizeX) * (std::size_t(y) + std::size_t(kSizeY) * z)]; }
  float at(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= kSizeX || y >= kSizeY || z >= kSizeZ) return 0.0f;
    return values[std::size_t(x) + std::size_t(kSizeX) * (std::size_t(y) + std::size_t(kSizeY) * z)];
  }
  // Trilinear at a voxel-space position (voxel centres at integers); zero outside.
  float sample(float x, float y, float z) const {
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y)), z0 = int(std::floor(z));
    const float tx = x - x0, ty = y - y0, tz = z - z0;
    float sum = 0.0f;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
          sum += (i ? tx : 1 - tx) * (j ? ty : 1 - ty) * (k ? tz : 1 - tz) * at(x0 + i, y0 + j, z0 + k);
    return sum;
  }
};

// Metres of voxel (x, y, z) from the plume's base centre.
openvdb::Vec3f position(int x, int y, int z) {
  return {(x - kSizeX / 2 + 0.5f) * kVoxel, (y + 0.5f) * kVoxel, (z - kSizeZ / 2 + 0.5f) * kVoxel};
}

// Wind in m/s at a point and time: heat lifts the smoke, and two swirls that drift with
// time curl it (their phases come from integer hashes, so every build writes the same).
openvdb::Vec3f velocity(const openvdb::Vec3f& p, float heat, float time) {
  const float swirl = 0.3f;
  const float u = swirl * std::sin(3.1f * p.y() + 2.3f * time + 6.28f * hash01(1)) +
                  0.25f * std::sin(5.3f * p.z() - 1.7f * time);
  const float w = swirl * std::cos(2.7f * p.y() - 1.9f * time + 6.28f * hash01(2)) +
                  0.25f * std::cos(4.9f * p.x() + 1.3f * time);
  return {u, 0.9f + 1.2f * heat, w};
}

struct Smoke {
  Field density, heat;
  float time = 0.0f;

  // Injects smoke and heat at the base, flickering by frame.
  void emit(int frame) {
    for (int z = 0; z < kSizeZ; ++z)
      for (int y = 1; y < 5; ++y)
        for (int x = 0; x < kSizeX; ++x) {
          const openvdb::Vec3f p = position(x, y, z);
          const float r = std::hypot(p.x(), p.z());
          if (r > 0.3f) continue;
          const float puff = 0.6f + 0.4f * hash01(uint32_t(x), uint32_t(z), uint32_t(frame) + 7u);
          density.at(x, y, z) = std::max(density.at(x, y, z), 6.0f * puff * (1.0f - r / 0.3f));
          heat.at(x, y, z) = 1.0f;
        }
  }

  void step(int frame) {
    emit(frame);
    Field next_density, next_heat;
    for (int z = 0; z < kSizeZ; ++z)
      for (int y = 0; y < kSizeY; ++y)
        for (int x = 0; x < kSizeX; ++x) {
          const openvdb::Vec3f back = velocity(position(x, y, z), heat.at(x, y, z), time) * (kStep / kVoxel);
          const float sx = x - back.x(), sy = y - back.y(), sz = z - back.z();
          next_density.at(x, y, z) = 0.997f * density.sample(sx, sy, sz);
          next_heat.at(x, y, z) = 0.98f * heat.sample(sx, sy, sz);
        }
    density = std::move(next_density);
    heat = std::move(next_heat);
    time += kStep;
  }

  void write(const std::filesystem::path& file) const {
    auto density_grid = openvdb::FloatGrid::create(0.0f);
    auto heat_grid = openvdb::FloatGrid::create(0.0f);
    auto velocity_grid = openvdb::Vec3SGrid::create(openvdb::Vec3f(0.0f));
    const auto transform = openvdb::math::Transform::createLinearTransform(kVoxel);
    transform->postTranslate(openvdb::Vec3d(-(kSizeX / 2 - 0.5) * kVoxel, 0.5 * kVoxel, -(kSizeZ / 2 - 0.5) * kVoxel));
    for (auto grid : std::initializer_list<openvdb::GridBase::Ptr>{density_grid, heat_grid, velocity_grid}) {
      grid->setTransform(transform->copy());
      grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    }
    density_grid->setName("density");
    heat_grid->setName("temperature");
    velocity_grid->setName("velocity");
    velocity_grid->setGridClass(openvdb::GRID_STAGGERED);
    auto d = density_grid->getAccessor();
    auto h = heat_grid->getAccessor();
    auto v = velocity_grid->getAccessor();
    for (int z = 0; z < kSizeZ; ++z)
      for (int y = 0; y < kSizeY; ++y)
        for (int x = 0; x < kSizeX; ++x) {
          const float value = density.at(x, y, z);
          if (value < 2e-3f) continue;
          const openvdb::Coord c(x, y, z);
          d.setValue(c, value);
          h.setValue(c, heat.at(x, y, z));
          v.setValue(c, velocity(position(x, y, z), heat.at(x, y, z), time));
        }
    openvdb::io::File vdb(file.string());
    vdb.write({density_grid, heat_grid, velocity_grid});
    vdb.close();
    make_uuid_deterministic(file);
  }
};

const char* const kSequenceScene = R"({
  "version": 1,
  "description": "A simulated smoke sequence (plume_sequence/plume.####.vdb, 24 frames of a buoyant plume in a swirling wind, written by avsm-make-content) playing at 24 fps on the default stage, under the default scene's sun and spot light.",
  "models": [
    { "name": "stage", "file": "stage.gltf" }
  ],
  "volumes": [
    {
      "name": "plume", "file": "plume_sequence/plume.####.vdb", "grid": "density",
      "sequence": { "frames": [1, 24], "fps": 24, "mode": "loop" },
      "transform": { "translation": [-1.2, 0.0, -0.4] },
      "extinction_scale": 6.0,
      "albedo": [0.9, 0.9, 0.9]
    }
  ],
  "lights": [
    {
      "name": "sun", "type": "directional",
      "direction": [0.35, -1.0, 0.25],
      "color": [1.0, 0.96, 0.9], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true }
    },
    {
      "name": "key_spot", "type": "spot",
      "position": [3.0, 3.6, 2.4], "target": [0.2, 0.9, -0.2],
      "inner_cone_deg": 24.0, "outer_cone_deg": 32.0,
      "color": [1.0, 0.9, 0.8], "intensity": 40.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "trilinear", "sort": true }
    }
  ],
  "cameras": [
    {
      "name": "main",
      "position": [0.2, 1.7, 5.8], "target": [-0.4, 1.1, 0.0], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 45.0, "near": 0.05, "far": 60.0
    }
  ]
}
)";

}  // namespace

void write_plume_sequence(const std::filesystem::path& scene_dir, const std::filesystem::path& dir, int frame_count) {
  openvdb::initialize();
  std::filesystem::create_directories(dir);
  Smoke smoke;
  for (int frame = -kPreRollFrames; frame < 1; ++frame) smoke.step(frame);
  for (int frame = 1; frame <= frame_count; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "plume.%04d.vdb", frame);
    smoke.write(dir / name);
    smoke.step(frame);
  }
  std::ofstream stream(scene_dir / "plume_sequence.scene.json");
  stream << kSequenceScene;
  if (!stream) throw std::runtime_error((scene_dir / "plume_sequence.scene.json").string() + ": cannot write");
}

}  // namespace avsm::content
