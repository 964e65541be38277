#pragma once
// Material alpha in the light captures (MeshDraw::alpha, shaders/common/caster_alpha.glsl):
// a draw that tests alpha binds its base-colour texture by push descriptor, as the camera's
// opaque pass does (no descriptor indexing: lavapipe lacks the non-uniform kind), and
// pushes its mode, cutoff and factor with the pass's push constants. Opaque draws keep
// the fast path: one binding for all of them and no texture fetch.
#include <cstdint>
#include <string>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/shadows/shadow_casters.h"
#include "scene/mesh.h"

namespace avsm::passes {

// A glTF material texture (RGBA8) uploaded for sampling, in SHADER_READ_ONLY_OPTIMAL. Colours
// (base colour, emissive) are sRGB-encoded, data (metallic-roughness, normal, occlusion)
// linear: the format decodes each as glTF means it (an sRGB format leaves alpha linear).
gpu::Image upload_material_texture(const gpu::Context& ctx, uint32_t width, uint32_t height, const uint8_t* rgba8,
                                   scene::ColorSpace color_space, const std::string& name);

// `draw` with `material`'s alpha: its mode, cutoff and factor, and `texture` (the view of
// its base-colour texture, VK_NULL_HANDLE for none).
MeshDraw with_material_alpha(MeshDraw draw, const scene::Material& material, VkImageView texture);

// What a capture pass binds for alpha: the draw's texture (white for draws without one)
// and a linear, repeating sampler.
// Records `draw` (the pass has bound the index buffer).
inline void draw_mesh(VkCommandBuffer cmd, const MeshDraw& draw) {
  vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, draw.vertex_offset, 0);
}

class CasterAlphaTextures {
 public:
  explicit CasterAlphaTextures(const gpu::Context& ctx);
  // Binds `draw`'s texture as "base_color_texture".
  void bind(gpu::Bindings& bindings, const MeshDraw& draw) const;
  // Sets the GPU_CASTER_ALPHA_PUSH members of a pass's push constants for `draw`.
  template <class Push>
  static void set_push(Push& push, const MeshDraw& draw) {
    push.alpha_mode = uint32_t(draw.alpha);
    push.alpha_cutoff = draw.alpha_cutoff;
    push.alpha_factor = draw.alpha_factor;
  }

 private:
  gpu::Sampler sampler_;
  gpu::Image white_;
};

}  // namespace avsm::passes
