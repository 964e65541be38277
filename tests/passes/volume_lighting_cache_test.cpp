// The lighting cache's cell layout (VolumeLightingCachePass::plan): pure CPU, no device.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <stdexcept>

#include "passes/camera/volumes/volume_lighting_cache_pass.h"
#include "scene/camera.h"

namespace avsm::passes {
namespace volume_lighting_cache_test {  // one per file: test targets are unity builds
namespace {

// A 64 x 32 x 16 voxel support of 0.01-unit voxels, its corner at the world origin.
VolumeBox box(float downsample = 2.0f) {
  VolumeBox b;
  b.world_from_index = glm::scale(glm::mat4(1.0f), glm::vec3(0.01f));
  b.support_min = glm::vec3(0.0f);
  b.support_max = glm::vec3(64.0f, 32.0f, 16.0f);
  b.voxel_size = 0.01f;
  b.brick_size = 8;
  b.world_bounds = {glm::vec3(0.0f), glm::vec3(0.64f, 0.32f, 0.16f)};
  b.cache_downsample = downsample;
  return b;
}

View view_from(float distance, uint32_t width = 1280, uint32_t height = 720) {
  scene::Camera camera;
  camera.position = glm::vec3(0.32f, 0.16f, 0.16f + distance);
  camera.target = glm::vec3(0.32f, 0.16f, 0.0f);
  return make_view(camera, width, height);
}

TEST(VolumeLightingCachePlan, NearVolumeUsesTheSceneDownsample) {
  const std::vector<GpuCacheLayout> layouts = VolumeLightingCachePass::plan({box(2.0f)}, view_from(0.5f), 2, 2048);
  ASSERT_EQ(layouts.size(), 1u);
  EXPECT_EQ(layouts[0].dims, glm::ivec3(32, 16, 8));
  EXPECT_EQ(layouts[0].first_slice, 0);
  EXPECT_EQ(layouts[0].cells_per_voxel, glm::vec3(0.5f));
  // Cell (0.5, 0.5, 0.5) is the centre of the first two voxels: index (1, 1, 1), world 0.01.
  const glm::vec4 centre = layouts[0].world_from_cell * glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  EXPECT_NEAR(centre.x, 0.01f, 1e-6f);
  EXPECT_NEAR(centre.z, 0.01f, 1e-6f);
}

TEST(VolumeLightingCachePlan, CellsCoarsenWithDistanceUpToABrick) {
  // A march pixel (divisor 2) at 20 units covers 20 * 2 * tan(22.5 deg) / 720 * 2 ~ 0.046,
  // about 4.6 voxels: the cells follow it.
  const GpuCacheLayout far = VolumeLightingCachePass::plan({box()}, view_from(20.0f), 2, 2048)[0];
  EXPECT_LT(far.dims.x, 16);
  EXPECT_GE(far.dims.x, 8);
  // Very far: never coarser than a brick (8 voxels).
  const GpuCacheLayout very_far = VolumeLightingCachePass::plan({box()}, view_from(1000.0f), 2, 2048)[0];
  EXPECT_EQ(very_far.dims, glm::ivec3(8, 4, 2));
  // A finer march resolution keeps finer cells.
  const GpuCacheLayout full_resolution = VolumeLightingCachePass::plan({box()}, view_from(20.0f), 1, 2048)[0];
  EXPECT_GT(full_resolution.dims.x, far.dims.x);
}

TEST(VolumeLightingCachePlan, VolumesStackAlongZAndCoarsenToFitTheImageLimit) {
  const std::vector<GpuCacheLayout> layouts =
      VolumeLightingCachePass::plan({box(1.0f), box(1.0f)}, view_from(0.5f), 1, 2048);
  EXPECT_EQ(layouts[0].dims, glm::ivec3(64, 32, 16));
  EXPECT_EQ(layouts[1].first_slice, 16);
  // 24 slices allowed: 16 + 16 does not fit, coarser cells do.
  const std::vector<GpuCacheLayout> fitted =
      VolumeLightingCachePass::plan({box(1.0f), box(1.0f)}, view_from(0.5f), 1, 24);
  EXPECT_LE(fitted[1].first_slice + fitted[1].dims.z, 24);
  EXPECT_LE(fitted[0].dims.x, 24);
  // Not even brick-sized cells fit two slices: a clear error.
  EXPECT_THROW(VolumeLightingCachePass::plan({box(), box()}, view_from(0.5f), 1, 2), std::invalid_argument);
}

}  // namespace
}  // namespace volume_lighting_cache_test
}  // namespace avsm::passes
