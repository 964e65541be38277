#pragma once
// A scene's glTF material textures on the GPU, as the camera's opaque pass and the light
// captures (alpha) sample them: each image with its mip chain (scene::Texture::mips), read
// through a sampler made from its glTF sampler (one per distinct one), and a white 1 x 1
// texture for materials without one.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gpu/resources.h"
#include "scene/mesh.h"

namespace avsm::passes {

// A glTF material texture (RGBA8, every level it has) uploaded for sampling, in
// SHADER_READ_ONLY_OPTIMAL. Colours (base colour, emissive) are sRGB-encoded, data
// (metallic-roughness, normal, occlusion) linear: the format decodes each as glTF means it
// (an sRGB format leaves alpha linear).
gpu::Image upload_material_texture(const gpu::Context& ctx, const scene::Texture& texture, const std::string& name);

// The Vulkan sampler state of a glTF sampler. Without mipmaps, level 0 alone is read
// (MIPMAP_MODE_NEAREST with a maximum LOD of 0.25, as the Vulkan specification suggests).
gpu::SamplerDesc material_sampler_desc(const scene::TextureSampler& sampler);

class MaterialTextures {
 public:
  explicit MaterialTextures(const gpu::Context& ctx);
  void upload(const std::vector<scene::Texture>& textures);
  // Texture `index` of the scene's list; -1 (or out of range): the white texture with a
  // default sampler.
  VkImageView view(int index) const;
  VkSampler sampler(int index) const;

 private:
  const gpu::Context& ctx_;
  std::vector<gpu::Image> images_;
  std::vector<VkSampler> image_samplers_;  // per image, owned by samplers_
  std::map<scene::TextureSampler, gpu::Sampler> samplers_;
  gpu::Image white_;
  gpu::Sampler default_sampler_;
};

}  // namespace avsm::passes
