#include "passes/frame/material_textures.h"

#include "gpu/context.h"
#include "gpu/transfer.h"

namespace avsm::passes {
namespace {

VkSamplerAddressMode address_mode(scene::TextureWrap wrap) {
  switch (wrap) {
    case scene::TextureWrap::clamp_to_edge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case scene::TextureWrap::mirrored_repeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case scene::TextureWrap::repeat: break;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

VkFilter filter(scene::TextureFilter f) { return f == scene::TextureFilter::nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }

}  // namespace

gpu::Image upload_material_texture(const gpu::Context& ctx, const scene::Texture& texture, const std::string& name) {
  gpu::ImageDesc desc;
  desc.width = texture.width;
  desc.height = texture.height;
  desc.mip_levels = texture.mip_levels();
  desc.format = texture.color_space == scene::ColorSpace::srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = name;
  gpu::Image image = gpu::Image::create(ctx, desc);
  std::vector<std::span<const std::uint8_t>> levels = {texture.rgba8};
  for (const std::vector<std::uint8_t>& mip : texture.mips) levels.emplace_back(mip);
  gpu::upload_image_levels(ctx, image, levels, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  return image;
}

gpu::SamplerDesc material_sampler_desc(const scene::TextureSampler& sampler) {
  gpu::SamplerDesc desc;
  desc.filter = filter(sampler.mag);
  desc.min_filter = filter(sampler.min);
  desc.address = address_mode(sampler.wrap_u);
  desc.address_v = address_mode(sampler.wrap_v);
  desc.mip_mode = sampler.mipmapped && sampler.mip == scene::TextureFilter::linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR
                                                                                   : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  if (!sampler.mipmapped) desc.max_lod = 0.25f;
  desc.name = "material sampler";
  return desc;
}

MaterialTextures::MaterialTextures(const gpu::Context& ctx) : ctx_(ctx), default_sampler_(ctx, material_sampler_desc({})) {
  scene::Texture white;
  white.width = white.height = 1;
  white.rgba8 = {255, 255, 255, 255};  // 1.0 as sRGB and as UNORM
  white_ = upload_material_texture(ctx, white, "white texture");
}

void MaterialTextures::upload(const std::vector<scene::Texture>& textures) {
  images_.clear();
  image_samplers_.clear();
  for (const scene::Texture& texture : textures) {
    images_.push_back(upload_material_texture(ctx_, texture, "texture " + texture.name));
    auto found = samplers_.find(texture.sampler);
    if (found == samplers_.end())
      found = samplers_.emplace(texture.sampler, gpu::Sampler(ctx_, material_sampler_desc(texture.sampler))).first;
    image_samplers_.push_back(found->second.handle());
  }
}

VkImageView MaterialTextures::view(int index) const {
  return index >= 0 && size_t(index) < images_.size() ? images_[index].view() : white_.view();
}

VkSampler MaterialTextures::sampler(int index) const {
  return index >= 0 && size_t(index) < image_samplers_.size() ? image_samplers_[index] : default_sampler_.handle();
}

}  // namespace avsm::passes
