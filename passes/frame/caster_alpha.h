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

// `draw` with `material`'s alpha: its mode, cutoff and factor, and `texture` and `sampler`
// (its base-colour texture's view and sampler, VK_NULL_HANDLE for none).
MeshDraw with_material_alpha(MeshDraw draw, const scene::Material& material, VkImageView texture, VkSampler sampler);

// What a capture pass binds for alpha: the draw's texture and sampler (white, and a
// linear repeating sampler, for draws without one).
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
