#pragma once
// Opaque glTF geometry from the camera: depth + lit HDR colour. Shading is glTF's
// metallic-roughness BRDF (shaders/common/pbr_brdf.glsl) with normal, occlusion and
// emissive textures, lit by every light attenuated by its transmittance map
// (shaders/common/shadow_lookup.glsl, passes/shadows/shadow_maps.h), the sky, and emission.
// All meshes share one vertex, one tangent and one index buffer; a draw per mesh
// pushes its material index and binds its textures.
#include <rendergraph/graph.h>

#include <array>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "gpu/resources.h"
#include "passes/frame/material_textures.h"
#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/shadow_maps_fwd.h"
#include "passes/frame/view.h"
#include "scene/scene.h"

namespace avsm::passes {

struct FrameInputs;  // passes/frame/frame_inputs.h

class OpaquePass {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
  // Area lights that look up subsets of their virtual lights (shared/area_shadows.h):
  // their unshadowed light and subsets' transmittance, for AreaShadowFilterPass.
  static constexpr VkFormat kAreaLightFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

  OpaquePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  void set_scene(const scene::Scene& scene);
  // Mesh `mesh` of the scene set (its index in scene.meshes) as it now is: the same
  // vertex count and triangles, moved or deformed. Uploads its vertices (waiting for the
  // copy; no frame may be in flight). Throws std::invalid_argument for another count.
  void update_mesh(uint32_t mesh, const scene::Mesh& now);

  struct Outputs {
    rg::TextureHandle color;  // written as ColorAttachment
    rg::TextureHandle depth;  // written as DepthAttachmentWrite
    rg::BufferHandle page_requests;  // the paged maps' request bits, marked (invalid without paged maps)
    rg::TextureHandle area_light;    // with area-light subsets: kAreaLightFormat, written as ColorAttachment
  };
  // The geometry as shadow casters (vertices are CasterVertex; passes/shadows/capture/capture_opaque_pass.h).
  MeshCasters casters() const;

  // Clears `color` to the sky colour and a new transient depth buffer to far,
  // then draws every mesh. With `area_light_subsets`, area lights with more virtual lights
  // than kAreaShadowLookups look up a subset per pixel and go to Outputs::area_light
  // instead of `color` (AreaShadowFilterPass adds them).
  Outputs add_to_graph(rg::Graph& graph, rg::TextureHandle color, FrameInputs& frame, bool area_light_subsets = false);

 private:
  struct Draw {
    uint32_t first_index, index_count;
    int32_t vertex_offset;
    uint32_t material;
  };
  void record(rg::PassContext& c, const Outputs& targets, const View& view, const gpu::Buffer& lights,
              uint32_t light_count, const ShadowInputs& shadows) const;
  gpu::Pipeline create_pipeline(const gpu::ShaderLibrary& shaders, bool area_light_subsets) const;

  gpu::Context& ctx_;
  const gpu::ShaderLibrary& shaders_;
  gpu::Pipeline pipeline_;
  // Made on the first frame that needs it: lavapipe compiles a pipeline as it is made, and
  // most renderers never light with an area light.
  gpu::Pipeline area_subsets_pipeline_;
  // The LTC table of rect lights (engine/lighting/ltc.h, common/area_light.glsl): M^-1's
  // coefficients and the lobe's magnitudes, filtered bilinearly.
  gpu::Image ltc_matrix_, ltc_magnitude_;
  gpu::Sampler ltc_sampler_;
  gpu::Buffer vertices_, tangents_, indices_, materials_;
  MaterialTextures textures_;
  std::vector<Draw> draws_;
  struct VertexRange {
    uint32_t first, count;
  };
  std::vector<VertexRange> mesh_vertices_;  // per scene mesh, in vertices_ and tangents_
  std::vector<scene::Material> scene_materials_;  // their textures per draw, and their alpha as casters
};

}  // namespace avsm::passes
