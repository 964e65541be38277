#include "passes/frame/caster_alpha.h"

#include "gpu/context.h"
#include "passes/frame/material_textures.h"

namespace avsm::passes {

MeshDraw with_material_alpha(MeshDraw draw, const scene::Material& material, VkImageView texture, VkSampler sampler) {
  switch (material.alpha_mode) {
    case scene::AlphaMode::opaque: draw.alpha = CasterAlpha::opaque; break;
    case scene::AlphaMode::mask: draw.alpha = CasterAlpha::mask; break;
    case scene::AlphaMode::blend: draw.alpha = CasterAlpha::blend; break;
  }
  draw.alpha_cutoff = material.alpha_cutoff;
  draw.alpha_factor = material.base_color_factor.a;
  draw.alpha_texture = texture;
  draw.alpha_sampler = sampler;
  return draw;
}

CasterAlphaTextures::CasterAlphaTextures(const gpu::Context& ctx)
    : sampler_(ctx, {VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT}) {
  scene::Texture white;
  white.width = white.height = 1;
  white.rgba8 = {255, 255, 255, 255};
  white_ = upload_material_texture(ctx, white, "caster alpha: white texture");
}

void CasterAlphaTextures::bind(gpu::Bindings& bindings, const MeshDraw& draw) const {
  const bool textured = draw.alpha_texture != VK_NULL_HANDLE;
  bindings.image("base_color_texture", textured ? draw.alpha_texture : white_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 textured ? draw.alpha_sampler : sampler_.handle());
}

}  // namespace avsm::passes
