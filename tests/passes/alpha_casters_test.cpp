// Material alpha in the shadow maps (MeshDraw::alpha, passes/frame/caster_alpha.h): under a
// directional light, a masked quad whose texture is a checker of alpha 0 and 1 (cutoff
// 0.5) lets the light through its holes and blocks it elsewhere, built from lists and
// in fixed memory; blended quads (alpha from factor x texture, and from the factor
// alone) let 1 - alpha through in the lists build and block nothing in the fixed one.
#include <gtest/gtest.h>

#include <rendergraph/vulkan/executor.h>

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "passes/frame/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "support/gpu_test.h"

namespace avsm {
namespace alpha_casters_test {  // one per file: test targets are unity builds
namespace {

using AlphaCastersTest = testing::GpuTest;

constexpr float kQuadHeight = 1.0f;  // the casters lie in y = 1, the probes in y = 0
constexpr float kQuadSize = 2.0f;
constexpr int kCheckerCells = 4;     // per side: cells of 0.5 m
constexpr uint8_t kBlendTextureAlpha = 128;
constexpr float kBlendFactorAlpha = 0.6f;      // x 128/255: alpha 0.30
constexpr float kUntexturedBlendAlpha = 0.5f;  // the factor alone

// A horizontal quad at y = kQuadHeight with its low corner at (x, z), uv 0..1 across it.
scene::Mesh quad(float x, float z, uint32_t material) {
  scene::Mesh mesh;
  mesh.name = "quad " + std::to_string(material);
  for (int corner = 0; corner < 4; ++corner) {
    const float u = float(corner & 1), v = float(corner >> 1);
    mesh.positions.emplace_back(x + u * kQuadSize, kQuadHeight, z + v * kQuadSize);
    mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
    mesh.uvs.emplace_back(u, v);
    mesh.bounds.extend(mesh.positions.back());
  }
  mesh.indices = {0, 2, 1, 1, 2, 3};
  mesh.material = material;
  return mesh;
}

// A checker of kCheckerCells^2 texels, alpha 255 where (x + y) is even, else 0.
scene::Texture checker_texture() {
  scene::Texture texture{"checker", kCheckerCells, kCheckerCells, {}};
  for (int y = 0; y < kCheckerCells; ++y)
    for (int x = 0; x < kCheckerCells; ++x)
      texture.rgba8.insert(texture.rgba8.end(), {200, 200, 200, uint8_t((x + y) % 2 == 0 ? 255 : 0)});
  return texture;
}

scene::Material material(const std::string& name, scene::AlphaMode mode, float factor_alpha, int texture) {
  scene::Material m;
  m.name = name;
  m.alpha_mode = mode;
  m.base_color_factor.a = factor_alpha;
  m.base_color_texture = texture;
  return m;
}

struct AlphaScene {
  scene::Scene scene;
  std::vector<glm::vec3> probes;  // see the constructor for which is where
  std::vector<bool> under_hole;   // the masked quad's probes: behind a hole?
  size_t first_blend_probe = 0;   // then: 4 behind the textured blend quad, 4 behind the untextured one
};

// Three quads side by side under a slanted sun: masked checker, textured blend,
// untextured blend. Probes lie where the light reaches y = 0 through each masked cell
// centre and through four points of each blended quad.
AlphaScene alpha_scene(scene::ShadowBuild build) {
  AlphaScene s;
  scene::Scene& scene = s.scene;
  scene.file = "alpha casters test scene (built in the test)";
  scene.textures = {checker_texture(), {"half alpha", 1, 1, {255, 255, 255, kBlendTextureAlpha}}};
  scene.materials = {material("masked checker", scene::AlphaMode::mask, 1.0f, 0),
                     material("blend textured", scene::AlphaMode::blend, kBlendFactorAlpha, 1),
                     material("blend factor", scene::AlphaMode::blend, kUntexturedBlendAlpha, -1)};
  const float x0 = -3.5f, gap = 0.5f, z0 = -1.0f;
  for (uint32_t m = 0; m < 3; ++m) scene.meshes.push_back(quad(x0 + float(m) * (kQuadSize + gap), z0, m));

  scene::Light sun;
  sun.name = "sun";
  sun.type = scene::LightType::directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.shadow.technique = "avsm";
  sun.shadow.nodes = 8;
  sun.shadow.resolution = 256;
  sun.shadow.fit = scene::ShadowFit::scene;
  sun.shadow.build = build;
  scene.lights.push_back(sun);

  // From a point of a quad to where its shadow falls on y = 0.
  const auto behind = [&](float x, float z) {
    return glm::vec3(x, kQuadHeight, z) + sun.direction * (kQuadHeight / -sun.direction.y);
  };
  const float cell = kQuadSize / kCheckerCells;
  for (int v = 0; v < kCheckerCells; ++v)
    for (int u = 0; u < kCheckerCells; ++u) {
      s.probes.push_back(behind(x0 + (float(u) + 0.5f) * cell, z0 + (float(v) + 0.5f) * cell));
      s.under_hole.push_back((u + v) % 2 != 0);
    }
  s.first_blend_probe = s.probes.size();
  for (uint32_t m = 1; m < 3; ++m)
    for (const glm::vec2 at : {glm::vec2(0.3f, 0.3f), glm::vec2(0.7f, 0.4f), glm::vec2(0.4f, 0.7f), glm::vec2(0.6f)})
      s.probes.push_back(behind(x0 + float(m) * (kQuadSize + gap) + at.x * kQuadSize, z0 + at.y * kQuadSize));

  for (const scene::Mesh& mesh : scene.meshes) scene.bounds.extend(mesh.bounds);
  for (const glm::vec3& p : s.probes) scene.bounds.extend(p);  // the receivers
  scene::Camera camera;
  camera.position = glm::vec3(0.0f, 6.0f, 8.0f);
  camera.target = glm::vec3(0.0f);
  scene.cameras.push_back(camera);
  return s;
}

std::vector<float> render_probes(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const AlphaScene& s) {
  constexpr uint32_t kWidth = 64, kHeight = 36;
  renderer::SceneRenderer renderer(ctx, shaders, s.scene, kWidth, kHeight);
  renderer.set_probes(s.probes);
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  for (int frame = 0; frame < 2; ++frame) {
    rg::Graph graph = renderer.build_frame(passes::make_view(s.scene.cameras.front(), kWidth, kHeight));
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    renderer.finish_frame();
  }
  return renderer.probe_results().at(0);
}

TEST_F(AlphaCastersTest, MaskedHolesLetLightThroughAndBlendedCastersAreTranslucent) {
  const float textured_blend_alpha = kBlendFactorAlpha * float(kBlendTextureAlpha) / 255.0f;
  for (scene::ShadowBuild build : {scene::ShadowBuild::lists, scene::ShadowBuild::fixed}) {
    SCOPED_TRACE(scene::to_string(build));
    const AlphaScene s = alpha_scene(build);
    const std::vector<float> got = render_probes(ctx(), shaders(), s);
    ASSERT_EQ(got.size(), s.probes.size());
    for (size_t i = 0; i < s.under_hole.size(); ++i)
      EXPECT_NEAR(got[i], s.under_hole[i] ? 1.0f : 0.0f, 0.02f) << "checker cell " << i;
    // Lists: a translucent occluder. Fixed: no partial blocker has a place there, so
    // translucent texels cast nothing (content/README.md, "Alpha").
    const bool lists = build == scene::ShadowBuild::lists;
    for (size_t i = 0; i < 8; ++i) {
      const float alpha = i < 4 ? textured_blend_alpha : kUntexturedBlendAlpha;
      EXPECT_NEAR(got[s.first_blend_probe + i], lists ? 1.0f - alpha : 1.0f, 0.02f) << "blend probe " << i;
    }
    std::cout << "[ alpha casters ] " << scene::to_string(build) << ": behind a hole " << got[1] << ", solid "
              << got[0] << ", blend " << textured_blend_alpha << ": " << got[s.first_blend_probe] << ", blend "
              << kUntexturedBlendAlpha << ": " << got[s.first_blend_probe + 4] << "\n";
  }
}

}  // namespace
}  // namespace alpha_casters_test
}  // namespace avsm
