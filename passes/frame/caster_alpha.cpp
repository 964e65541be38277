#include "passes/frame/caster_alpha.h"

#include "gpu/context.h"
#include "gpu/transfer.h"

namespace avsm::passes {

gpu::Image upload_material_texture(const gpu::Context& ctx, uint32_t width, uint32_t height, const uint8_t* rgba8,
                                   scene::ColorSpace color_space, const std::string& name) {
  gpu::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = color_space == scene::ColorSpace::srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = name;
  gpu::Image image = gpu::Image::create(ctx, desc);
  gpu::upload_image(ctx, image, rgba8, VkDeviceSize(width) * height * 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  return image;
}

MeshDraw with_material_alpha(MeshDraw draw, const scene::Material& material, VkImageView texture) {
  switch (material.alpha_mode) {
    case scene::AlphaMode::opaque: draw.alpha = CasterAlpha::opaque; break;
    case scene::AlphaMode::mask: draw.alpha = CasterAlpha::mask; break;
    case scene::AlphaMode::blend: draw.alpha = CasterAlpha::blend; break;
  }
  draw.alpha_cutoff = material.alpha_cutoff;
  draw.alpha_factor = material.base_color_factor.a;
  draw.alpha_texture = texture;
  return draw;
}

CasterAlphaTextures::CasterAlphaTextures(const gpu::Context& ctx)
    : sampler_(ctx, {VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT}) {
  const uint8_t white[4] = {255, 255, 255, 255};
  white_ = upload_material_texture(ctx, 1, 1, white, scene::ColorSpace::srgb, "caster alpha: white texture");
}

void CasterAlphaTextures::bind(gpu::Bindings& bindings, const MeshDraw& draw) const {
  const VkImageView view = draw.alpha_texture != VK_NULL_HANDLE ? draw.alpha_texture : white_.view();
  bindings.image("base_color_texture", view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.handle());
}

}  // namespace avsm::passes
