// Volumes: the real smoke1 sample against vdb_print and OpenVDB's own sampler,
// analytic transmittance through generated grids, and malformed input.
#include "support.h"

#include "scene/volume.h"
#include "scene/volume_scattering.h"

#include <nanovdb/NanoVDB.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

namespace avsm::scene {
namespace volume_test {  // one per file: test targets are unity builds
namespace {

using testing::TempDir;
using testing::load_error_of;

std::filesystem::path smoke_file() { return testing::shared_content("smoke1/smoke.vdb"); }

void write_grid(const std::filesystem::path& file, openvdb::GridBase::Ptr grid) {
  openvdb::initialize();
  openvdb::io::File vdb(file.string());
  vdb.write({grid});
  vdb.close();
}

// A cube of constant density over voxels [0, n-1]^3.
openvdb::FloatGrid::Ptr constant_cube(int n, float density, float voxel_size) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(n - 1)), density, true);
  return grid;
}

// Deterministic points in a box.
struct PointStream {
  std::uint32_t state = 12345;
  float next() {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / 16777216.0f;
  }
  glm::vec3 in(const Bounds& box) { return box.min + glm::vec3(next(), next(), next()) * box.size(); }
};

TEST(Volume, SmokeStatisticsMatchVdbPrint) {
  AVSM_REQUIRE_FILE(smoke_file());
  const Volume volume = load_vdb_volume(smoke_file());
  // Expected values from: vdb_print -l -m ../shared/content/smoke1/smoke.vdb
  //   Min value: 1.00136e-05   Max value: 5.71484
  //   Number of active voxels: 1,049,275   Number of active tiles: 0
  //   Bounding box of active voxels: [1, 2, 1] -> [111, 223, 112]
  //   voxel size: 0.476, index to world translation [-34, -13.1, -26.4] (printed to 3 digits)
  EXPECT_EQ(volume.stats.active_voxel_count, 1049275u);
  EXPECT_NEAR(volume.stats.min, 1.00136e-05f, 1e-9f);
  EXPECT_NEAR(volume.stats.max, 5.71484f, 1e-5f);
  EXPECT_EQ(volume.active_index_min, glm::ivec3(1, 2, 1));
  EXPECT_EQ(volume.active_index_max, glm::ivec3(111, 223, 112));
  const glm::vec3 origin = glm::vec3(volume.world_from_index * glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(origin.x, -34.0f, 0.05f);
  EXPECT_NEAR(origin.y, -13.1f, 0.05f);
  EXPECT_NEAR(origin.z, -26.4f, 0.05f);
  EXPECT_NEAR(volume.world_from_index[0][0], 0.476f, 0.0005f);
  // vdb_print has no mean; NanoVDB's converter computes one independently.
  const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
  EXPECT_NEAR(volume.stats.mean, grid->tree().root().average(), 1e-4);
  EXPECT_GT(volume.stats.mean, 0.0);
}

TEST(Volume, SmokeNanoVdbBufferIsOneValidAlignedGrid) {
  AVSM_REQUIRE_FILE(smoke_file());
  const Volume volume = load_vdb_volume(smoke_file());
  ASSERT_FALSE(volume.nanovdb.empty());
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(volume.nanovdb.data()) % 32, 0u);
  const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
  ASSERT_TRUE(grid->isValid());
  EXPECT_EQ(grid->gridType(), nanovdb::GridType::Float);
  EXPECT_EQ(grid->gridSize(), volume.nanovdb.size());
  EXPECT_STREQ(grid->gridName(), "density");
  EXPECT_EQ(grid->activeVoxelCount(), 1049275u);
  EXPECT_EQ(volume.name, "smoke");
}

TEST(Volume, SmokeSamplerAgreesWithOpenVdbBoxSampler) {
  AVSM_REQUIRE_FILE(smoke_file());
  const Volume volume = load_vdb_volume(smoke_file());
  openvdb::initialize();
  openvdb::io::File vdb(smoke_file().string());
  vdb.open();
  const auto reference = openvdb::gridPtrCast<openvdb::FloatGrid>(vdb.readGrid("density"));
  const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*reference);
  PointStream points;
  int nonzero = 0;
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 p = points.in(volume.world_bounds);
    const float expected = float(sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z)));
    ASSERT_NEAR(sample_density(volume, p), expected, 1e-5f * (1.0f + expected)) << "at " << p.x << " " << p.y << " " << p.z;
    nonzero += expected > 0.0f;
  }
  EXPECT_GT(nonzero, 500);
  // Exactly the voxel's value at its centre (integer index coordinates).
  const glm::vec3 centre = glm::vec3(volume.world_from_index * glm::vec4(50, 100, 50, 1));
  EXPECT_FLOAT_EQ(sample_density(volume, centre), reference->tree().getValue(openvdb::Coord(50, 100, 50)));
}

TEST(Volume, SmokeMajorantBoundsTheDensityEverywhere) {
  AVSM_REQUIRE_FILE(smoke_file());
  const Volume volume = load_vdb_volume(smoke_file());
  const MajorantGrid& m = volume.majorant;
  EXPECT_EQ(m.brick_size, 8);
  EXPECT_EQ(m.index_origin, glm::ivec3(0, 1, 0));
  EXPECT_EQ(m.dims, glm::ivec3(14, 28, 15));  // ceil((max + 1 - origin) / 8)
  EXPECT_FLOAT_EQ(*std::max_element(m.max_density.begin(), m.max_density.end()), volume.stats.max);
  EXPECT_GT(std::count(m.max_density.begin(), m.max_density.end(), 0.0f), 0);  // empty bricks to skip
  PointStream points;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 p = points.in(volume.world_bounds);
    const glm::vec3 brick_coord = glm::vec3(glm::inverse(volume.world_from_majorant) * glm::vec4(p, 1.0f));
    const glm::ivec3 brick = glm::clamp(glm::ivec3(glm::floor(brick_coord)), glm::ivec3(0), m.dims - 1);
    ASSERT_LE(sample_density(volume, p), m.at(brick) * (1.0f + 1e-5f) + 1e-7f);
  }
}

TEST(Volume, TransmittanceThroughAConstantCubeIsAnalytic) {
  TempDir dir;
  constexpr int n = 20;
  constexpr float density = 0.5f, voxel = 0.1f, scale = 3.0f;
  write_grid(dir / "cube.vdb", constant_cube(n, density, voxel));
  VolumeOptions options;
  options.extinction_scale = scale;
  const Volume volume = load_vdb_volume(dir / "cube.vdb", options);
  EXPECT_EQ(volume.stats.active_voxel_count, std::uint64_t(n * n * n));
  EXPECT_DOUBLE_EQ(volume.stats.mean, density);
  // Along an axis through the interior, trilinear density is flat over
  // [0, n-1] and ramps to 0 over one voxel at each end: integral = d * n voxels.
  const float y = 10 * voxel, z = 7.3f * voxel;
  const float expected_depth = scale * density * n * voxel;
  const glm::vec3 a(-1.0f, y, z), b(3.0f, y, z);
  EXPECT_NEAR(optical_depth(volume, a, b), expected_depth, 1e-3f * expected_depth);
  EXPECT_NEAR(transmittance(volume, a, b), std::exp(-expected_depth), 1e-4f);
  EXPECT_NEAR(transmittance(volume, b, a), std::exp(-expected_depth), 1e-4f);
  EXPECT_FLOAT_EQ(transmittance(volume, glm::vec3(-1, 5, 5), glm::vec3(3, 5, 5)), 1.0f);  // misses
  // Half the way in: flat part from index 0 to 5 plus the entry ramp.
  EXPECT_NEAR(optical_depth(volume, a, glm::vec3(0.5f, y, z)), scale * density * 5.5f * voxel, 1e-3f);
}

// The escape chance at the brick corner nearest a constant cube's centre lies between the
// transmittances along the shortest and the longest way out, and a corner outside escapes
// more; the sky's light summed over octaves exceeds the first octave's (the escape chance)
// by what the later octaves add, and more octaves add more.
TEST(Volume, SkyLightingOfAConstantCubeLiesBetweenItsShortestAndLongestWayOut) {
  TempDir dir;
  constexpr int n = 24;
  constexpr float voxel = 0.1f, sigma = 1.5f;  // per world unit
  write_grid(dir / "cube.vdb", constant_cube(n, 1.0f, voxel));
  VolumeOptions options;
  options.extinction_scale = sigma;
  options.albedo = glm::vec3(1.0f, 0.5f, 0.0f);
  Volume volume = load_vdb_volume(dir / "cube.vdb", options);
  const MajorantGrid& m = volume.majorant;
  const glm::ivec3 dims = m.dims + 1;
  const glm::ivec3 centre = glm::ivec3(glm::round((glm::vec3(11.5f) - glm::vec3(m.index_origin)) / float(m.brick_size)));
  auto corner = [&](const std::vector<float>& grid, glm::ivec3 c) {
    const float* at = grid.data() + 4 * std::size_t(c.x + dims.x * (c.y + dims.y * c.z));
    return glm::vec4(at[0], at[1], at[2], at[3]);
  };
  volume.multiple_scattering = {1, 0.5f, 1.0f};
  const std::vector<float> single = sky_lighting(volume);
  ASSERT_EQ(single.size(), 4 * sky_lighting_corners(volume));
  volume.multiple_scattering = {4, 0.5f, 1.0f};
  const std::vector<float> four = sky_lighting(volume);
  const glm::vec4 inside = corner(four, centre);
  // Its way out through the flat density runs at least to the nearest face of [0, n - 1] and
  // at most to the support's farthest corner.
  const glm::vec3 p = glm::vec3(m.index_origin + centre * m.brick_size);
  const float nearest_face = std::min({p.x, p.y, p.z, n - 1 - p.x, n - 1 - p.y, n - 1 - p.z});
  const float farthest = glm::length(glm::max(p + 1.0f, glm::vec3(n) - p));
  EXPECT_LE(inside.a, std::exp(-sigma * voxel * nearest_face));
  EXPECT_GE(inside.a, std::exp(-sigma * voxel * farthest));
  const glm::vec4 outside = corner(four, glm::ivec3(0));
  EXPECT_GT(outside.a, inside.a);
  EXPECT_LT(outside.a, 1.0f);
  // One octave: the sky's light is the escape chance itself, whatever the albedo.
  EXPECT_FLOAT_EQ(corner(single, centre).r, inside.a);
  EXPECT_FLOAT_EQ(corner(single, centre).b, inside.a);
  // Four: later octaves add light in proportion to the albedo (none in blue).
  EXPECT_GT(inside.r, inside.g);
  EXPECT_GT(inside.g, inside.a);
  EXPECT_FLOAT_EQ(inside.b, inside.a);
  for (float v : four) ASSERT_TRUE(v >= 0.0f && std::isfinite(v)) << v;
}

// The path tracer against the one multiple-scattering answer known in closed form: a medium
// that absorbs nothing, under a uniform sky from every direction, sends back exactly the
// sky's radiance along every ray, whatever its density (what it scatters in makes up for
// what it takes out). With albedo 0 it scatters nothing and only attenuates.
TEST(Volume, PathTracedNonAbsorbingCubeUnderAUniformSkyReturnsTheSky) {
  TempDir dir;
  write_grid(dir / "cube.vdb", constant_cube(16, 1.0f, 0.1f));
  VolumeOptions options;
  options.extinction_scale = 4.0f;  // optical depth 6.4 across
  options.albedo = glm::vec3(1.0f);
  const Volume white = load_vdb_volume(dir / "cube.vdb", options);
  const glm::vec3 sky(1.0f);
  const PathTracing tracing{20000, 100000, 7};
  for (const glm::vec3 origin : {glm::vec3(0.75f, 0.75f, 5.0f), glm::vec3(0.3f, 1.1f, 5.0f)}) {
    const PathTracedRay ray = path_trace(white, {}, sky, origin, glm::vec3(0.0f, 0.0f, -1.0f), tracing);
    EXPECT_LT(ray.transmittance, 0.01f);
    EXPECT_NEAR(ray.in_scattered.g + ray.transmittance * sky.g, 1.0f, 0.03f) << origin.x << ", " << origin.y;
  }
  options.albedo = glm::vec3(0.0f);
  const Volume black = load_vdb_volume(dir / "cube.vdb", options);
  Light sun;
  const PathTracedRay ray = path_trace(black, std::vector<Light>{sun}, sky, glm::vec3(0.75f, 0.75f, 5.0f),
                                       glm::vec3(0.0f, 0.0f, -1.0f), {64, 256, 7});
  EXPECT_EQ(ray.in_scattered, glm::vec3(0.0f));
  EXPECT_NEAR(ray.transmittance, std::exp(-4.0f * 1.6f), 1e-3f);
}

TEST(Volume, PlacementScalesTheOpticalDepth) {
  TempDir dir;
  write_grid(dir / "cube.vdb", constant_cube(10, 1.0f, 0.1f));
  VolumeOptions options;
  options.transform = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0)), glm::vec3(2.0f));
  const Volume volume = load_vdb_volume(dir / "cube.vdb", options);
  // World: the cube spans x in [5, 7] (10 voxels of 0.2); depth = 1 * 10 voxels * 0.2.
  EXPECT_NEAR(volume.world_bounds.min.x, 5.0f - 0.2f, 1e-5f);
  EXPECT_NEAR(optical_depth(volume, glm::vec3(0, 1, 1), glm::vec3(10, 1, 1)), 2.0f, 2e-3f);
  EXPECT_NEAR(sample_density(volume, glm::vec3(6, 1, 1)), 1.0f, 1e-6f);
}

TEST(Volume, SmokeOpticalDepthAgreesWithAnIndependentOpenVdbMarch) {
  AVSM_REQUIRE_FILE(smoke_file());
  VolumeOptions options;
  options.extinction_scale = 0.2f;
  const Volume volume = load_vdb_volume(smoke_file(), options);
  openvdb::initialize();
  openvdb::io::File vdb(smoke_file().string());
  vdb.open();
  const auto reference = openvdb::gridPtrCast<openvdb::FloatGrid>(vdb.readGrid("density"));
  const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*reference);
  // Vertical and slanted rays through the plume; plain fixed-step trapezoid, no skipping.
  const glm::vec3 rays[][2] = {{{-8, -20, 0}, {-8, 100, 0}}, {{-40, 40, -30}, {25, 60, 30}}, {{0, 80, -30}, {-10, 10, 30}}};
  for (const auto& ray : rays) {
    const int steps = 20000;
    double sum = 0.0;
    for (int i = 0; i <= steps; ++i) {
      const glm::vec3 p = glm::mix(ray[0], ray[1], float(i) / steps);
      const double d = std::max(0.0, double(sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z))));
      sum += (i == 0 || i == steps) ? 0.5 * d : d;
    }
    const double expected = 0.2 * sum * glm::length(ray[1] - ray[0]) / steps;
    EXPECT_GT(expected, 0.5);
    EXPECT_NEAR(optical_depth(volume, ray[0], ray[1]), expected, 0.005 * expected);
  }
}

// ---- bad input ----

TEST(VolumeErrors, MissingFileAndWrongMagic) {
  TempDir dir;
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "absent.vdb"); }), HasSubstr("absent.vdb: file not found"));
  testing::write_text(dir / "text.vdb", "not a volume at all");
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "text.vdb"); }), HasSubstr("text.vdb: not an OpenVDB file"));
}

TEST(VolumeErrors, TruncatedFile) {
  AVSM_REQUIRE_FILE(smoke_file());
  TempDir dir;
  const auto bytes = testing::read_bytes(smoke_file());
  // OpenVDB itself reads truncated grids without complaint (missing values
  // come back as zeros); the framing check must catch every cut.
  for (std::size_t size : {std::size_t(12), std::size_t(30), std::size_t(200), bytes.size() / 2, bytes.size() - 1}) {
    testing::write_bytes(dir / "cut.vdb", {bytes.begin(), bytes.begin() + size});
    EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "cut.vdb"); }), HasSubstr("cut.vdb: file is truncated: ")) << size;
  }
  testing::write_bytes(dir / "cut.vdb", {bytes.begin(), bytes.end() - 1});
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "cut.vdb"); }),
              HasSubstr("data of grid 'density' ends at byte 2511715 but the file has 2511714 bytes"));
}

TEST(VolumeErrors, MissingGridListsThoseThere) {
  AVSM_REQUIRE_FILE(smoke_file());
  VolumeOptions options;
  options.grid_name = "temperature";
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(smoke_file(), options); }),
              HasSubstr("smoke.vdb: no grid named 'temperature' (grids in the file: 'density')"));
}

TEST(VolumeErrors, GridsThatAreNotFogDensity) {
  TempDir dir;
  auto vectors = openvdb::Vec3SGrid::create();
  vectors->setName("density");
  vectors->tree().setValue(openvdb::Coord(0), openvdb::Vec3s(1, 2, 3));
  write_grid(dir / "vec.vdb", vectors);
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "vec.vdb"); }), HasSubstr("grid 'density' holds Tree_vec3s_5_4_3 values, not float density"));

  auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0), 0.1f);
  sphere->setName("density");
  write_grid(dir / "sphere.vdb", sphere);
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "sphere.vdb"); }), HasSubstr("is a level set"));

  auto background = constant_cube(4, 1.0f, 1.0f);
  background->tree().root().setBackground(0.5f, false);
  write_grid(dir / "background.vdb", background);
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "background.vdb"); }), HasSubstr("has background 0.5"));

  auto empty = openvdb::FloatGrid::create(0.0f);
  empty->setName("density");
  write_grid(dir / "empty.vdb", empty);
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "empty.vdb"); }), HasSubstr("has no active voxels"));

  auto nan = constant_cube(4, 1.0f, 1.0f);
  nan->tree().setValue(openvdb::Coord(1, 2, 3), std::numeric_limits<float>::quiet_NaN());
  write_grid(dir / "nan.vdb", nan);
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "nan.vdb"); }), HasSubstr("non-finite value at voxel [1, 2, 3]"));
}

TEST(VolumeErrors, BadOptions) {
  TempDir dir;
  write_grid(dir / "cube.vdb", constant_cube(4, 1.0f, 1.0f));
  VolumeOptions options;
  options.majorant_brick_size = 1;
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "cube.vdb", options); }), HasSubstr("majorant brick size 1"));
  options.majorant_brick_size = 8;
  options.transform = glm::scale(glm::mat4(1.0f), glm::vec3(1, 0, 1));
  EXPECT_THAT(load_error_of([&] { load_vdb_volume(dir / "cube.vdb", options); }), HasSubstr("singular"));
}

}  // namespace
}  // namespace volume_test
}  // namespace avsm::scene
