// The flicker figure (capture/flicker.h): frame-to-frame transmittance changes at fixed
// points, the first frame kept apart, lights weighed by their share of the light; and the
// probe points under a grid of pixels.
#include <gtest/gtest.h>

#include "capture/flicker.h"

namespace avsm::capture {
namespace flicker_test {  // one per file: test targets are unity builds
namespace {

TEST(FlickerMeter, MeasuresChangesAfterTheFirstFrame) {
  FlickerMeter meter({"sun", "spot"}, {0.75, 0.25});
  meter.add_frame({{0.0f, 0.0f}, {0.0f, 0.0f}});  // the first frame: its change is not counted
  meter.add_frame({{1.0f, 1.0f}, {1.0f, 1.0f}});
  meter.add_frame({{1.0f, 0.5f}, {1.0f, 1.0f}});  // the sun changes 0.5 at one point
  meter.add_frame({{1.0f, 0.5f}, {0.0f, 1.0f}});  // the spot changes 1 at the other
  const FlickerReport report = meter.report();
  EXPECT_EQ(report.points, 2u);
  EXPECT_EQ(report.frame_pairs, 2u);
  ASSERT_EQ(report.lights.size(), 2u);
  EXPECT_EQ(report.lights[0].light, "sun");
  EXPECT_DOUBLE_EQ(report.lights[0].mean, 0.5 / 4.0);
  EXPECT_DOUBLE_EQ(report.lights[0].max, 0.5);
  EXPECT_DOUBLE_EQ(report.lights[1].mean, 1.0 / 4.0);
  EXPECT_DOUBLE_EQ(report.lights[0].share_over_tenth, 1.0 / 4.0);
  // ΔL: (0.75 x 0.5 + 0.25 x 1) over 2 points x 2 pairs.
  EXPECT_DOUBLE_EQ(report.mean_delta_l, (0.75 * 0.5 + 0.25 * 1.0) / 4.0);
  EXPECT_THROW(meter.add_frame({{1.0f, 1.0f}}), std::invalid_argument);

  // An unfinished frame's changes, to it and from it, are left out.
  meter.add_frame({{0.0f, 0.0f}, {0.0f, 0.0f}}, /*unfinished=*/true);
  meter.add_frame({{1.0f, 0.5f}, {0.0f, 1.0f}});
  EXPECT_EQ(meter.report().frame_pairs, 2u);
  EXPECT_EQ(meter.report().unfinished_frames, 1u);
  meter.add_frame({{1.0f, 0.5f}, {0.0f, 1.0f}});
  EXPECT_EQ(meter.report().frame_pairs, 3u);
}

TEST(FlickerProbes, PointsUnderAGridOfPixelsFaceTheCamera) {
  scene::Scene scene;
  scene::Mesh quad;  // the plane z = 0, 2 x 2 around the origin
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.bounds.extend(glm::vec3(-1, -1, 0));
  quad.bounds.extend(glm::vec3(1, 1, 0));
  scene.meshes.push_back(quad);
  scene::Camera camera;
  camera.position = {0, 0, 2};
  camera.target = {0, 0, 0};
  camera.vertical_fov = 1.5707963f;  // 90 degrees: the quad fills the middle half of the image
  const FlickerProbes probes = flicker_probes(scene, passes::make_view(camera, 8, 8), 8, 8);
  EXPECT_EQ(probes.points.size(), 16u);
  for (std::size_t i = 0; i < probes.points.size(); ++i) {
    EXPECT_NEAR(probes.points[i].z, 0.0f, 1e-5f);
    EXPECT_NEAR(probes.normals[i].z, 1.0f, 1e-5f);  // towards the camera, whatever the winding
  }
}

}  // namespace
}  // namespace flicker_test
}  // namespace avsm::capture
