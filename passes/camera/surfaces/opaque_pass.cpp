#include "passes/camera/surfaces/opaque_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "gpu/rendering.h"
#include "gpu/transfer.h"
#include "lighting/ltc.h"
#include "passes/frame/caster_alpha.h"
#include "passes/shadows/shadow_maps.h"
#include "shared/passes/camera/surfaces/opaque.h"
#include "passes/frame/frame_inputs.h"

namespace avsm::passes {

namespace {

using GpuVertex = CasterVertex;  // the captures read the same vertex buffer
using shared::GpuMaterial;      // shaders/shared/mesh.h
using OpaquePush = shared::OpaquePush;  // shaders/shared/passes/camera/surfaces/opaque.h

constexpr glm::vec4 kSkyColor{0.35f, 0.45f, 0.6f, 1.0f};

GpuMaterial gpu_material(const scene::Material& m) {
  GpuMaterial g{};
  g.base_color = m.base_color_factor;
  g.alpha_mask = m.alpha_mode == scene::AlphaMode::mask ? 1u : 0u;
  g.alpha_cutoff = m.alpha_cutoff;
  g.has_texture = m.base_color_texture >= 0 ? 1u : 0u;
  g.metallic = m.metallic_factor;
  g.emissive = glm::vec4(m.emissive, 0.0f);
  g.roughness = m.roughness_factor;
  g.normal_scale = m.normal_scale;
  g.occlusion_strength = m.occlusion_strength;
  g.has_normal_texture = m.normal_texture >= 0 ? 1u : 0u;
  return g;
}

// One table of the LTC fit as a size x size texture: x the view angle, y the roughness.
gpu::Image ltc_table_image(const gpu::Context& ctx, uint32_t size, VkFormat format, const void* texels,
                           VkDeviceSize bytes, const char* name) {
  gpu::ImageDesc desc;
  desc.width = desc.height = size;
  desc.format = format;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = name;
  gpu::Image image = gpu::Image::create(ctx, desc);
  gpu::upload_image(ctx, image, texels, bytes, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  return image;
}

// For meshes without a material: grey, rough, not metallic.
scene::Material fallback_material() {
  scene::Material m;
  m.base_color_factor = glm::vec4(0.8f);
  m.metallic_factor = 0.0f;
  return m;
}

}  // namespace

OpaquePass::OpaquePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      shaders_(shaders),
      ltc_sampler_(ctx, {VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE}),
      textures_(ctx) {
  pipeline_ = create_pipeline(shaders, false);
  const lighting::LtcTable& table = lighting::builtin_ggx_table();
  ltc_matrix_ = ltc_table_image(ctx, table.size, VK_FORMAT_R32G32B32A32_SFLOAT, table.inverse_matrix.data(),
                                table.inverse_matrix.size() * sizeof(glm::vec4), "ltc inverse matrices");
  ltc_magnitude_ = ltc_table_image(ctx, table.size, VK_FORMAT_R32G32_SFLOAT, table.magnitude.data(),
                                   table.magnitude.size() * sizeof(glm::vec2), "ltc magnitudes");
}

gpu::Pipeline OpaquePass::create_pipeline(const gpu::ShaderLibrary& shaders, bool area_light_subsets) const {
  gpu::GraphicsPipelineDesc desc;
  desc.name = area_light_subsets ? "opaque (area-light subsets)" : "opaque";
  desc.vertex = shaders.load("shaders/passes/camera/surfaces/opaque.vert");
  desc.fragment = area_light_subsets ? shaders.load("shaders/passes/camera/surfaces/opaque.frag",
                                                    {"AVSM_AREA_SHADOW_SUBSETS", "1"})
                                     : shaders.load("shaders/passes/camera/surfaces/opaque.frag");
  desc.color_formats = {kColorFormat};
  if (area_light_subsets) desc.color_formats.push_back(kAreaLightFormat);
  desc.depth_format = kDepthFormat;
  desc.depth_test = desc.depth_write = true;
  desc.cull_mode = VK_CULL_MODE_NONE;  // glTF double-sided flags vary; shading uses the facing normal
  return gpu::Pipeline::graphics(ctx_, desc);
}

namespace {

// The mesh's vertices as the shaders read them, and their tangents (zero without).
void append_vertices(const scene::Mesh& mesh, std::vector<GpuVertex>& vertices, std::vector<glm::vec4>& tangents) {
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0, 1, 0);
    glm::vec2 uv = v < mesh.uvs.size() ? mesh.uvs[v] : glm::vec2(0);
    const glm::vec3& p = mesh.positions[v];
    vertices.push_back({{p.x, p.y, p.z}, {n.x, n.y, n.z}, {uv.x, uv.y}});
    tangents.push_back(v < mesh.tangents.size() ? mesh.tangents[v] : glm::vec4(0.0f));
  }
}

}  // namespace

void OpaquePass::update_mesh(uint32_t mesh, const scene::Mesh& now) {
  const VertexRange range = mesh_vertices_.at(mesh);
  if (now.positions.size() != range.count)
    throw std::invalid_argument("mesh '" + now.name + "': " + std::to_string(now.positions.size()) +
                                " vertices where the scene had " + std::to_string(range.count) +
                                "; set the scene again to change its topology");
  if (range.count == 0) return;
  std::vector<GpuVertex> vertices;
  std::vector<glm::vec4> tangents;
  append_vertices(now, vertices, tangents);
  gpu::upload_buffer(ctx_, vertices_, vertices.data(), vertices.size() * sizeof(GpuVertex),
                     range.first * sizeof(GpuVertex));
  gpu::upload_buffer(ctx_, tangents_, tangents.data(), tangents.size() * sizeof(glm::vec4),
                     range.first * sizeof(glm::vec4));
}

void OpaquePass::set_scene(const scene::Scene& scene) {
  std::vector<GpuVertex> vertices;
  std::vector<glm::vec4> tangents;  // parallel to vertices
  std::vector<uint32_t> indices;
  draws_.clear();
  mesh_vertices_.clear();
  for (const scene::Mesh& mesh : scene.meshes) {
    Draw draw{uint32_t(indices.size()), uint32_t(mesh.indices.size()), int32_t(vertices.size()), mesh.material};
    mesh_vertices_.push_back({uint32_t(vertices.size()), uint32_t(mesh.positions.size())});
    append_vertices(mesh, vertices, tangents);
    indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    if (draw.index_count > 0) draws_.push_back(draw);
  }
  std::vector<GpuMaterial> materials;
  scene_materials_ = scene.materials;
  for (const scene::Material& m : scene.materials) materials.push_back(gpu_material(m));
  if (materials.empty()) materials.push_back(gpu_material(fallback_material()));
  if (tangents.empty()) tangents.emplace_back(0.0f);  // no zero-sized buffers
  vertices_ = gpu::create_buffer_from(ctx_, std::move(vertices), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "opaque vertices");
  tangents_ = gpu::create_buffer_from(ctx_, std::move(tangents), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "opaque tangents");
  indices_ = gpu::create_buffer_from(ctx_, std::move(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "opaque indices");
  materials_ = gpu::create_buffer_from(ctx_, std::move(materials), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "opaque materials");
  textures_.upload(scene.textures);
}

MeshCasters OpaquePass::casters() const {
  MeshCasters casters{vertices_.handle(), vertices_.size(), indices_.handle(), indices_.size(), {}};
  for (const Draw& draw : draws_) {
    const MeshDraw range{draw.first_index, draw.index_count, draw.vertex_offset};
    if (draw.material >= scene_materials_.size()) {
      casters.draws.push_back(range);  // the grey default material: opaque
      continue;
    }
    const scene::Material& material = scene_materials_[draw.material];
    const int texture = material.base_color_texture;
    casters.draws.push_back(with_material_alpha(range, material, texture >= 0 ? textures_.view(texture) : VK_NULL_HANDLE,
                                                textures_.sampler(texture)));
  }
  return casters;
}

OpaquePass::Outputs OpaquePass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, FrameInputs& frame,
                                             bool area_light_subsets) {
  if (area_light_subsets && !area_subsets_pipeline_) area_subsets_pipeline_ = create_pipeline(shaders_, true);
  const View& view = frame.view;
  const gpu::Buffer& lights = *frame.lights;
  const uint32_t light_count = frame.light_count;
  const ShadowInputs shadows = frame.shadows;
  const Outputs& out = graph.add_pass<Outputs>("opaque", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, Outputs& d) {
        d.color = b.write(color, rg::Usage::ColorAttachment);
        rg::TextureDesc depth_desc{view.width, view.height, 1, 1, 1, kDepthFormat, kCameraSizeSetting};
        d.depth = b.write(b.create_texture("depth", depth_desc), rg::Usage::DepthAttachmentWrite);
        if (area_light_subsets) {
          rg::TextureDesc area_desc{view.width, view.height, 1, 1, 1, kAreaLightFormat, kCameraSizeSetting};
          d.area_light = b.write(b.create_texture("area light", area_desc), rg::Usage::ColorAttachment);
        }
        shadows.declare_reads(b);
        d.page_requests = frame.ask_for_pages(b);
      },
      [this, view, &lights, light_count, shadows](const Outputs& d, rg::PassContext& c) {
        record(c, d, view, lights, light_count, shadows);
      });
  return out;
}

void OpaquePass::record(rg::PassContext& c, const Outputs& targets, const View& view, const gpu::Buffer& lights,
                        uint32_t light_count, const ShadowInputs& shadows) const {
  VkCommandBuffer cmd = c.cmd();
  gpu::ColorTarget color{c.view(targets.color), c.layout(targets.color),
                         {{kSkyColor.r, kSkyColor.g, kSkyColor.b, kSkyColor.a}}};
  gpu::DepthTarget depth{c.view(targets.depth), c.layout(targets.depth), 1.0f, /*store=*/true};
  std::vector<gpu::ColorTarget> colors{color};
  const bool area_light_subsets = targets.area_light.valid();
  if (area_light_subsets)  // no area light: none of its light, nothing in its shadow
    colors.push_back({c.view(targets.area_light), c.layout(targets.area_light), {{0.0f, 0.0f, 0.0f, 1.0f}}});
  gpu::begin_rendering(cmd, {view.width, view.height}, colors, &depth, /*flip_y=*/true);
  const gpu::Pipeline& pipeline = area_light_subsets ? area_subsets_pipeline_ : pipeline_;
  pipeline.bind(cmd);
  vkCmdBindIndexBuffer(cmd, indices_.handle(), 0, VK_INDEX_TYPE_UINT32);
  static constexpr const char* kTextureBindings[] = {"base_color_texture", "metallic_roughness_texture", "normal_texture",
                                                     "occlusion_texture", "emissive_texture"};  // Material::textures() order
  for (const Draw& draw : draws_) {
    const scene::Material* material = draw.material < scene_materials_.size() ? &scene_materials_[draw.material] : nullptr;
    gpu::Bindings bindings(ctx_, pipeline);
    bindings.buffer("Vertices", vertices_).buffer("Tangents", tangents_).buffer("Materials", materials_).buffer("Lights", lights);
    for (size_t i = 0; i < std::size(kTextureBindings); ++i) {
      const int texture = material ? *material->textures()[i] : -1;  // -1: the white texture
      bindings.image(kTextureBindings[i], textures_.view(texture), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, textures_.sampler(texture));
    }
    bindings.image("ltc_matrix_table", ltc_matrix_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, ltc_sampler_.handle())
        .image("ltc_magnitude_table", ltc_magnitude_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
               ltc_sampler_.handle());
    shadows.bind(bindings, c);
    shadows.bind_page_requests(bindings, c, targets.page_requests);
    bindings.push(cmd);
    pipeline.push_constants(cmd, OpaquePush{view.view_projection, glm::vec4(view.camera_position, 1.0f),
                                             draw.material, light_count});
    vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, draw.vertex_offset, 0);
  }
  vkCmdEndRendering(cmd);
}

}  // namespace avsm::passes
