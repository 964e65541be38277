// The embedding API on the device: set_lights and pass_list run their precondition
// checks (shadows_preconditions_test.cpp covers each one) before anything changes; the
// pass list is whole and in the usage table's terms; add_to_graph runs it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>

#include <rendergraph/usage.h>
#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <set>

#include "avsm/shadows_rendergraph.h"
#include "gpu/barriers.h"
#include "gpu/transfer.h"
#include "support/gpu_test.h"

namespace avsm {
namespace shadows_api_test {  // one per file: test targets are unity builds
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

// The box every test's light covers, and its one small directional light.
Bounds unit_box() {
  Bounds bounds;
  bounds.extend(glm::vec3(-1.0f));
  bounds.extend(glm::vec3(1.0f));
  return bounds;
}

Light small_sun() {
  Light sun;
  sun.name = "sun";
  sun.resolution = 16;
  return sun;
}

TEST_F(ShadowsApiTest, ChecksRunBeforeAnythingChanges) {
  const std::string missing = message_of([&] { Shadows(ctx(), ShaderLocation{"/no/such/dir", "/no/such/dir"}); });
  EXPECT_NE(missing.find("avsm::Shadows: the shader folder /no/such/dir/shaders does not exist"), std::string::npos)
      << missing;

  Shadows shadows(ctx(), ShaderLocation::of_package());
  const Bounds bounds = unit_box();
  const Light sun = small_sun();
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
  EXPECT_NE(message_of([&] { add_to_graph(graph, shadows, Camera(), casters); })
                .find("avsm::Shadows::pass_list: casters.meshes.draws[0]: indices 0..6 exceed the index buffer"),
            std::string::npos);
  EXPECT_TRUE(graph.passes().empty());

  // Nothing to cast, a valid camera: the light's passes are declared.
  EXPECT_NO_THROW(add_to_graph(graph, shadows, Camera(), ShadowCasters()));
  EXPECT_FALSE(graph.passes().empty());
}

// What a host's graph relies on: names that tell passes and resources apart, uses of
// listed resources in the usage table's terms, transients written before they are read
// and created with every usage they see, persistent buffers with their handles, and the
// lookup's resources written by the frame.
void expect_whole_and_in_usage_table_terms(const ShadowPassList& list) {
  ASSERT_FALSE(list.passes.empty());
  std::set<std::string> pass_names, resource_names;
  for (const ShadowPass& pass : list.passes) EXPECT_TRUE(pass_names.insert(pass.name).second) << pass.name;
  for (const PassResource& r : list.resources) EXPECT_TRUE(resource_names.insert(r.name).second) << r.name;

  std::vector<bool> written(list.resources.size(), false);
  std::vector<VkImageUsageFlags> image_usage(list.resources.size(), 0);
  std::vector<VkBufferUsageFlags> buffer_usage(list.resources.size(), 0);
  for (const ShadowPass& pass : list.passes) {
    EXPECT_TRUE(pass.record) << pass.name;
    const rg::QueueType queue = pass.queue == PassQueue::graphics  ? rg::QueueType::Graphics
                                : pass.queue == PassQueue::compute ? rg::QueueType::Compute
                                                                   : rg::QueueType::Transfer;
    for (const PassResourceUse& use : pass.uses) {
      ASSERT_LT(use.resource, list.resources.size()) << pass.name;
      const PassResource& r = list.resources[use.resource];
      const std::string who = pass.name + " / " + r.name;
      if (r.transient) {
        EXPECT_TRUE(written[use.resource] || (use.writes && !use.reads)) << who << ": read before written";
      } else {
        EXPECT_EQ(r.kind, PassResource::Kind::buffer) << who;
        EXPECT_NE(r.handle, VK_NULL_HANDLE) << who;
      }
      written[use.resource] = written[use.resource] || use.writes;
      rg::UsageInfo expected;
      ASSERT_FALSE(use.usages.empty()) << who;
      for (const std::string& name : use.usages) {
        bool known = false;
        for (uint32_t u = 0; u < rg::kUsageCount; ++u) {
          if (name != rg::to_string(rg::Usage(u))) continue;
          known = true;
          const rg::UsageInfo info = rg::usage_info(rg::Usage(u), queue);
          expected.stages |= info.stages;
          expected.access |= info.access;
          expected.layout = info.layout;
          EXPECT_EQ(info.is_write && !use.writes, false) << who << ": writes as " << name;
          image_usage[use.resource] |= info.image_usage;
          buffer_usage[use.resource] |= info.buffer_usage;
        }
        EXPECT_TRUE(known) << who << ": " << name;
      }
      EXPECT_EQ(use.stages, expected.stages) << who;
      EXPECT_EQ(use.access, expected.access) << who;
      if (r.kind == PassResource::Kind::image) {
        EXPECT_EQ(use.layout, expected.layout) << who;
      }
    }
  }
  for (size_t i = 0; i < list.resources.size(); ++i) {
    const PassResource& r = list.resources[i];
    if (!r.transient) continue;
    if (r.kind == PassResource::Kind::image) {
      EXPECT_EQ(r.image.usage, image_usage[i]) << r.name;
    } else {
      EXPECT_EQ(r.buffer.usage, buffer_usage[i]) << r.name;
    }
    EXPECT_GT(r.kind == PassResource::Kind::image ? uint64_t(r.image.width) * r.image.height : r.buffer.size, 0u)
        << r.name;
  }
  ASSERT_NE(list.lookup.records, kNoPassResource);
  EXPECT_TRUE(written[list.lookup.records]);
  ASSERT_EQ(list.lookup.maps.size(), 1u);
  EXPECT_TRUE(written[list.lookup.maps[0]]);
  EXPECT_FALSE(list.resources[list.lookup.maps[0]].transient);
  EXPECT_NE(list.lookup.atlas.buffer, VK_NULL_HANDLE);
}

// A quad across the middle of the light's box: something to capture.
struct QuadCaster {
  gpu::Buffer vertices, indices;
  ShadowCasters casters;
};

QuadCaster quad_caster(const gpu::Context& ctx) {
  std::vector<CasterVertex> vertices;
  for (glm::vec2 c : {glm::vec2(-0.5f, -0.5f), glm::vec2(-0.5f, 0.5f), glm::vec2(0.5f, 0.5f), glm::vec2(0.5f, -0.5f)})
    vertices.push_back({{c.x, 0.0f, c.y}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f}});
  QuadCaster quad;
  quad.vertices = gpu::create_buffer_from(ctx, vertices, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "quad vertices");
  quad.indices = gpu::create_buffer_from(ctx, std::vector<uint32_t>{0, 1, 2, 0, 2, 3}, VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                         "quad indices");
  quad.casters.meshes.vertices = quad.vertices.handle();
  quad.casters.meshes.vertices_size = quad.vertices.size();
  quad.casters.meshes.indices = quad.indices.handle();
  quad.casters.meshes.indices_size = quad.indices.size();
  quad.casters.meshes.draws = {{0, 6, 0}};
  return quad;
}

// Runs `list` the way a host's graph of its own would, with nothing of the engine's graph:
// every transient its own allocation, and before each pass a full barrier that also moves
// each image to the layout its use asks for. Crude, but it is all the list asks of a host.
void run_as_foreign_host(const gpu::Context& ctx, const ShadowPassList& list) {
  std::vector<gpu::Buffer> buffers(list.resources.size());
  std::vector<gpu::Image> images(list.resources.size());
  std::vector<ResolvedResource> resolved(list.resources.size());
  std::vector<VkImageLayout> layouts(list.resources.size(), VK_IMAGE_LAYOUT_UNDEFINED);
  for (size_t i = 0; i < list.resources.size(); ++i) {
    const PassResource& r = list.resources[i];
    if (!r.transient) continue;  // the engine's: the pass uses the list's own handle
    if (r.kind == PassResource::Kind::image) {
      gpu::ImageDesc desc;
      desc.width = r.image.width;
      desc.height = r.image.height;
      desc.depth = r.image.depth;
      desc.volume = r.image.depth > 1;  // the fog's froxels
      desc.format = r.image.format;
      desc.usage = r.image.usage;
      desc.name = r.name;
      images[i] = gpu::Image::create(ctx, desc);
      resolved[i].image = images[i].handle();
      resolved[i].view = images[i].view();
    } else {
      buffers[i] = gpu::Buffer::create(ctx, {r.buffer.size, r.buffer.usage, gpu::MemoryLocation::DeviceLocal, r.name});
      resolved[i].buffer = buffers[i].handle();
    }
  }
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    const gpu::Access everything{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};
    for (const ShadowPass& pass : list.passes) {
      const VkMemoryBarrier2 memory = gpu::make_memory_barrier(everything, everything);
      std::vector<VkImageMemoryBarrier2> transitions;
      for (const PassResourceUse& use : pass.uses) {
        if (list.resources[use.resource].kind != PassResource::Kind::image) continue;
        const gpu::Image& image = images[use.resource];
        transitions.push_back(gpu::make_image_barrier(image.handle(), image.full_range(), layouts[use.resource],
                                                      use.layout, everything, everything));
        layouts[use.resource] = use.layout;
      }
      VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dependency.memoryBarrierCount = 1;
      dependency.pMemoryBarriers = &memory;
      dependency.imageMemoryBarrierCount = uint32_t(transitions.size());
      dependency.pImageMemoryBarriers = transitions.data();
      vkCmdPipelineBarrier2(cmd, &dependency);
      pass.record(cmd, resolved);
    }
  });
}

// One frame's pass list, for one light and a quad: whole and in the usage table's terms;
// through the engine's graph (add_to_graph), every listed pass in the plan, in list
// order, none culled; then scheduled by a host without the engine's graph, capturing
// what the engine's graph captured. All under validation with synchronization validation
// (TearDown fails on any message). A record function refuses a transient the host did
// not resolve, naming it. (One test: a Shadows costs lavapipe seconds of pipelines.)
TEST_F(ShadowsApiTest, PassListRunsThroughOurGraphAndAHostsOwn) {
  Shadows shadows(ctx(), ShaderLocation::of_package());
  shadows.set_light(small_sun(), unit_box());
  const QuadCaster quad = quad_caster(ctx());

  const ShadowPassList first = shadows.pass_list(Camera(), quad.casters);
  expect_whole_and_in_usage_table_terms(first);
  rg::Graph graph;
  const ShadowInputs inputs = add_to_graph(graph, first);
  EXPECT_TRUE(inputs.records.valid());
  EXPECT_EQ(inputs.maps.size(), 1u);
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
  EXPECT_TRUE(executor.plan().culled_passes.empty());
  ASSERT_EQ(executor.plan().passes.size(), first.passes.size());
  for (size_t p = 0; p < first.passes.size(); ++p) EXPECT_EQ(executor.plan().passes[p].name, first.passes[p].name);
  const uint64_t through_our_graph = shadows.finish_frame().at(0).segments_captured;
  EXPECT_GT(through_our_graph, 0u);

  const ShadowPassList list = shadows.pass_list(Camera(), quad.casters);
  run_as_foreign_host(ctx(), list);
  EXPECT_EQ(shadows.finish_frame().at(0).segments_captured, through_our_graph);

  for (const ShadowPass& pass : list.passes) {
    const auto transient = std::find_if(pass.uses.begin(), pass.uses.end(), [&](const PassResourceUse& use) {
      return list.resources[use.resource].transient;
    });
    if (transient == pass.uses.end()) continue;
    const std::string message = message_of([&] { pass.record(VK_NULL_HANDLE, {}); });
    EXPECT_NE(message.find("pass '" + pass.name + "': transient "), std::string::npos) << message;
    EXPECT_NE(message.find("'" + list.resources[transient->resource].name + "' has no"), std::string::npos) << message;
    break;
  }
}

// An area light through the API: its virtual lights' maps are one batch (one capture per
// caster kind), and the frame reports them all.
TEST_F(ShadowsApiTest, AnAreaLightsVirtualLightsAreOneBatch) {
  Shadows shadows(ctx(), ShaderLocation::of_package());
  Light softbox;
  softbox.name = "softbox";
  softbox.type = LightType::rect;
  softbox.position = {0.0f, 3.0f, 0.0f};
  softbox.size = {1.0f, 1.0f};
  softbox.virtual_lights = 16;
  softbox.resolution = 64;
  shadows.set_light(softbox, unit_box());
  const QuadCaster quad = quad_caster(ctx());
  const ShadowPassList list = shadows.pass_list(Camera(), quad.casters);
  expect_whole_and_in_usage_table_terms(list);
  const auto captures = std::count_if(list.passes.begin(), list.passes.end(), [](const ShadowPass& pass) {
    return pass.name.find("capture opaque") != std::string::npos;
  });
  EXPECT_EQ(captures, 1);
  run_as_foreign_host(ctx(), list);
  const LightStats stats = shadows.finish_frame().at(0);
  EXPECT_EQ(stats.maps, 16u);
  EXPECT_GT(stats.segments_captured, 0u);
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
  EXPECT_NE(lookup_buffers(shadows.unshadowed_lookup()).parameters.buffer, VK_NULL_HANDLE);
}

// The bytes of a buffer range the engine owns, copied back after the frames before.
std::vector<glm::vec4> read_range(const gpu::Context& ctx, const PassBufferRange& range, size_t count) {
  gpu::Buffer copy = gpu::Buffer::create(ctx, {count * sizeof(glm::vec4), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                               gpu::MemoryLocation::HostReadback, "fog grid copy"});
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    gpu::memory_barrier(cmd, {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT},
                        {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT});
    const VkBufferCopy region{range.offset, 0, count * sizeof(glm::vec4)};
    vkCmdCopyBuffer(cmd, range.buffer, copy.handle(), 1, &region);
  });
  std::vector<glm::vec4> values(count);
  std::memcpy(values.data(), copy.mapped(), count * sizeof(glm::vec4));
  return values;
}

float henyey_greenstein(float cos_theta, float g) {
  const float d = 1.0f + g * g - 2.0f * g * cos_theta;
  return (1.0f - g * g) / (4.0f * 3.14159265f * d * std::sqrt(d));
}

// The engine's fog through the API: set_fog checks its fog, and adds two passes at the end
// of the list, whose `fog` names the grid they write and the buffers a host's composite
// binds. Scheduled by a host of its own, with nothing to cast, the grid's last froxel of
// each column holds the closed form of a uniform fog under the sun along the column's
// centre ray. Switched off, the list has no fog pass and binds the parameters twice.
TEST_F(ShadowsApiTest, FogPassesComeWithTheListAndHoldTheFog) {
  Shadows shadows(ctx(), ShaderLocation::of_package());
  Light sun = small_sun();
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.6f));
  sun.radiance = glm::vec3(2.0f, 1.5f, 1.0f);
  shadows.set_light(sun, unit_box());
  Fog fog;
  fog.global = {.scattering = 0.2f, .absorption = 0.05f, .color = glm::vec3(1.0f, 0.9f, 0.8f), .phase_g = 0.4f};
  fog.grid = {.froxel_pixels = 8, .slices = 16, .distance = 4.0f};
  fog.sky_light = 0.0f;
  Fog bad = fog;
  bad.global.phase_g = 1.0f;
  EXPECT_NE(message_of([&] { shadows.set_fog(bad); })
                .find("avsm::Shadows::set_fog: fog.global.phase_g 1 must be -0.95 to 0.95"),
            std::string::npos);
  bad = fog;
  bad.boxes.push_back({Bounds{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 1.0f)}, {}});
  EXPECT_NE(message_of([&] { shadows.set_fog(bad); }).find("fog.boxes[0]: min (0, 0, 0) and max (1, 0, 1) must be"),
            std::string::npos);
  shadows.set_fog(fog);

  Camera camera;  // at the origin, looking down -z
  camera.height_pixels = 32;
  camera.aspect = 1.0f;  // 32 x 32 pixels: 4 x 4 columns of froxels
  const ShadowPassList list = shadows.pass_list(camera, ShadowCasters{});
  expect_whole_and_in_usage_table_terms(list);
  ASSERT_GE(list.passes.size(), 2u);
  EXPECT_EQ(list.passes[list.passes.size() - 2].name, "fog scattering");
  EXPECT_EQ(list.passes.back().name, "fog integration");
  ASSERT_NE(list.fog.integrated, kNoPassResource);
  EXPECT_FALSE(list.resources[list.fog.integrated].transient) << "the grid outlives the list";
  run_as_foreign_host(ctx(), list);
  shadows.finish_frame();

  constexpr uint32_t kColumns = 4, kSlices = 16;
  const std::vector<glm::vec4> grid = read_range(ctx(), list.fog.grid, kColumns * kColumns * kSlices);
  const float extinction = fog.global.scattering + fog.global.absorption;
  const float transmittance = std::exp(-extinction * fog.grid.distance);
  const float tangent = std::tan(0.5f * camera.vertical_fov_radians);
  double largest = 0.0;
  for (uint32_t y = 0; y < kColumns; ++y)
    for (uint32_t x = 0; x < kColumns; ++x) {
      const glm::vec2 ndc(2.0f * (float(x) + 0.5f) / kColumns - 1.0f, 1.0f - 2.0f * (float(y) + 0.5f) / kColumns);
      const glm::vec3 direction = glm::normalize(glm::vec3(ndc.x * tangent, ndc.y * tangent, -1.0f));
      const glm::vec3 scattered = fog.global.scattering * fog.global.color * sun.radiance *
                                  henyey_greenstein(glm::dot(-sun.direction, direction), fog.global.phase_g) *
                                  ((1.0f - transmittance) / extinction);
      const glm::vec4 got = grid[((kSlices - 1) * kColumns + y) * kColumns + x];
      for (int c = 0; c < 3; ++c) largest = std::max(largest, double(std::abs(got[c] - scattered[c]) / scattered[c]));
      EXPECT_NEAR(got.a, transmittance, 1e-4f) << "column " << x << ", " << y;
    }
  EXPECT_LT(largest, 1e-3) << "largest relative error of the in-scattered light";

  // Through the engine's graph: the grid among the reads a host's shading declares.
  rg::Graph graph;
  const ShadowInputs inputs = add_to_graph(graph, shadows.pass_list(camera, ShadowCasters{}));
  EXPECT_TRUE(inputs.fog_grid.valid());
  EXPECT_EQ(inputs.fog_grid_bytes.buffer, list.fog.grid.buffer);
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
  shadows.finish_frame();

  // record(): the same frame into a command buffer of the test's own, the fog's buffers
  // given back for the host's composite.
  ShadowFrame frame;
  frame.camera = camera;
  ctx().submit_and_wait([&](VkCommandBuffer cmd) {
    const ShadowLookupBuffers buffers = shadows.record(cmd, frame);
    EXPECT_EQ(buffers.fog_grid.buffer, list.fog.grid.buffer);
    EXPECT_NE(buffers.fog_grid.buffer, buffers.fog_parameters.buffer);
  });
  shadows.finish_frame();

  shadows.set_fog_enabled(false);
  const ShadowPassList off = shadows.pass_list(camera, ShadowCasters{});
  for (const ShadowPass& pass : off.passes) EXPECT_EQ(pass.name.find("fog"), std::string::npos) << pass.name;
  EXPECT_EQ(off.fog.integrated, kNoPassResource);
  EXPECT_EQ(off.fog.grid.buffer, off.fog.parameters.buffer);
  shadows.finish_frame();
}

}  // namespace
}  // namespace shadows_api_test
}  // namespace avsm
