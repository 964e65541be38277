// The embedding API on the device: set_lights and add_to_graph run their precondition
// checks (shadows_preconditions_test.cpp covers each one) before anything changes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "avsm/shadows.h"
#include "support/gpu_test.h"

namespace avsm {
namespace {

using ShadowsApiTest = testing::GpuTest;

std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST_F(ShadowsApiTest, ChecksRunBeforeAnythingChanges) {
  const std::string missing = message_of([&] { Shadows(ctx(), ShaderLocation{"/no/such/dir", "/no/such/dir"}); });
  EXPECT_NE(missing.find("avsm::Shadows: the shader folder /no/such/dir/shaders does not exist"), std::string::npos)
      << missing;

  Shadows shadows(ctx(), ShaderLocation::of_package());
  Bounds bounds;
  bounds.extend(glm::vec3(-1.0f));
  bounds.extend(glm::vec3(1.0f));
  Light sun;
  sun.name = "sun";
  sun.resolution = 16;
  Light bad = sun;
  bad.direction.y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(message_of([&] { shadows.set_light(bad, bounds); }).find("avsm::Shadows::set_lights: light 0 'sun': direction"),
            std::string::npos);
  shadows.set_light(sun, bounds);

  // Draws beyond their buffers: rejected before a pass is declared.
  ShadowCasters casters;
  casters.meshes.vertices = casters.meshes.indices = (VkBuffer)uintptr_t(0x10);  // never read: the check throws first
  casters.meshes.vertices_size = 3 * sizeof(CasterVertex);
  casters.meshes.indices_size = 3 * sizeof(uint32_t);
  casters.meshes.draws = {{0, 6, 0}};
  rg::Graph graph;
  EXPECT_NE(message_of([&] { shadows.add_to_graph(graph, Camera(), casters); })
                .find("avsm::Shadows::add_to_graph: casters.meshes.draws[0]: indices 0..6 exceed the index buffer"),
            std::string::npos);
  EXPECT_TRUE(graph.passes().empty());

  // Nothing to cast, a valid camera: the light's passes are declared.
  EXPECT_NO_THROW(shadows.add_to_graph(graph, Camera(), ShadowCasters()));
  EXPECT_FALSE(graph.passes().empty());
}

// record(): the same checks, naming record() and the field of its frame, before anything
// is recorded; then a frame recorded into a command buffer of the test's own.
TEST_F(ShadowsApiTest, RecordChecksItsFrameThenRecordsIntoTheHostsCommandBuffer) {
  Shadows shadows(ctx(), ShaderLocation::of_package());
  Bounds bounds;
  bounds.extend(glm::vec3(-1.0f));
  bounds.extend(glm::vec3(1.0f));
  Light sun;
  sun.resolution = 16;
  shadows.set_light(sun, bounds);

  ShadowFrame frame;
  EXPECT_NE(message_of([&] { shadows.record(VK_NULL_HANDLE, frame); }).find("avsm::Shadows::record: cmd is VK_NULL_HANDLE"),
            std::string::npos);
  ctx().submit_and_wait([&](VkCommandBuffer cmd) {
    ShadowFrame bad = frame;
    bad.casters_written.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    EXPECT_NE(message_of([&] { shadows.record(cmd, bad); })
                  .find("avsm::Shadows::record: frame.casters_written has access but no stages"),
              std::string::npos);
    bad = frame;
    bad.lookup_read_stages = VK_PIPELINE_STAGE_2_NONE;
    EXPECT_NE(message_of([&] { shadows.record(cmd, bad); }).find("avsm::Shadows::record: frame.lookup_read_stages is 0"),
              std::string::npos);
    bad = frame;
    bad.casters.meshes.vertices = bad.casters.meshes.indices = (VkBuffer)uintptr_t(0x10);  // never read
    bad.casters.meshes.vertices_size = 3 * sizeof(CasterVertex);
    bad.casters.meshes.indices_size = 3 * sizeof(uint32_t);
    bad.casters.meshes.draws = {{0, 6, 0}};
    EXPECT_NE(message_of([&] { shadows.record(cmd, bad); })
                  .find("avsm::Shadows::record: frame.casters.meshes.draws[0]: indices 0..6 exceed the index buffer"),
              std::string::npos);
    bad = frame;
    bad.frame_slot = 1;
    EXPECT_NE(message_of([&] { shadows.record(cmd, bad); }).find("frame slot 1 of 1 frames in flight"), std::string::npos);

    // Nothing to cast: the light's passes still run (clear, build), under validation.
    const ShadowLookupBuffers lookup = shadows.record(cmd, frame);
    EXPECT_NE(lookup.parameters.buffer, VK_NULL_HANDLE);
    EXPECT_NE(lookup.atlas.buffer, VK_NULL_HANDLE);
    EXPECT_EQ(lookup.parameters.range, VK_WHOLE_SIZE);
  });
  const std::vector<LightStats> stats = shadows.finish_frame();
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].segments_captured, 0u);
  EXPECT_NE(shadows.unshadowed_lookup().parameters.buffer, VK_NULL_HANDLE);
}

}  // namespace
}  // namespace avsm
