#pragma once
// What casts into the shadow maps, as plain views of GPU buffers: no scene format,
// no ownership. Each buffer comes with its size in bytes: the bytes of its elements at
// its start (a whole number of them, at most the VkBuffer's size), against which the
// embedding API (avsm/shadows.h) checks the counts and ranges it is given. The camera passes produce them for a loaded scene (OpaquePass::casters(),
// HairPass::casters(), VolumePass::casters()); a host renderer fills them from its own
// buffers. The buffers (and the draws' alpha textures) must hold their data before the
// frame is submitted and stay unchanged and alive until it completes: the captures read
// them as static data, outside the frame graph's synchronisation.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "shared/hair.h"
#include "shared/mesh.h"

namespace avsm::passes {

// One vertex as the opaque shaders read it (shaders/shared/mesh.h): the captures use
// the position, and the uv for draws that test alpha; the camera passes the rest.
using shared::CasterVertex;

// How a draw's material alpha casts (glTF's alphaMode; content/README.md "Alpha"):
// opaque blocks all light; mask blocks where alpha >= the cutoff and lets all light
// through elsewhere; blend lets 1 - alpha through, a translucent occluder like a hair
// fragment (in the fixed build, which keeps only the nearest blocker per texel, a blend
// caster blocks only where its alpha is 1).
enum class CasterAlpha : uint32_t {
  opaque = shared::kCasterAlphaOpaque,
  mask = shared::kCasterAlphaMask,
  blend = shared::kCasterAlphaBlend,
};

// A vkCmdDrawIndexed range of the shared index buffer, and its material's alpha.
// Alpha is alpha_factor times the alpha of `alpha_texture` at the vertices' uv
// (sampled linearly, repeating); without a texture, alpha_factor alone.
struct MeshDraw {
  uint32_t first_index = 0;
  uint32_t index_count = 0;
  int32_t vertex_offset = 0;
  CasterAlpha alpha = CasterAlpha::opaque;
  float alpha_cutoff = 0.5f;                   // mask only
  float alpha_factor = 1.0f;                   // the base colour factor's alpha
  VkImageView alpha_texture = VK_NULL_HANDLE;  // the base-colour texture, SHADER_READ_ONLY_OPTIMAL; mask, blend
  VkSampler alpha_sampler = VK_NULL_HANDLE;    // and its sampler
  bool tests_alpha() const { return alpha != CasterAlpha::opaque; }
};

// Triangle meshes, world space, drawn from both sides.
struct MeshCasters {
  VkBuffer vertices = VK_NULL_HANDLE;  // CasterVertex[]; usage STORAGE_BUFFER
  VkDeviceSize vertices_size = 0;      // bytes: sizeof(CasterVertex) x vertices
  VkBuffer indices = VK_NULL_HANDLE;   // uint32 triangle list; usage INDEX_BUFFER
  VkDeviceSize indices_size = 0;       // bytes: 4 x indices
  std::vector<MeshDraw> draws;
  bool empty() const { return draws.empty() || vertices == VK_NULL_HANDLE || indices == VK_NULL_HANDLE; }
};

// Strands as the hair shaders read them (shaders/shared/hair.h): a strand is a polyline
// of points; each segment joins point `first_point` and the next one. A strand's
// colour_opacity.a is its opacity per crossing (the capture stores 1 - opacity); its
// width is in world units (ribbons are widened to one map texel, opacity scaled down).
using shared::StrandSegment;
using StrandParameters = shared::Strand;

// Hair: ribbons facing the light.
struct StrandCasters {
  VkBuffer points = VK_NULL_HANDLE;    // vec4 per point (xyz world, w unused); usage STORAGE_BUFFER
  VkDeviceSize points_size = 0;        // bytes: 16 x points
  VkBuffer segments = VK_NULL_HANDLE;  // StrandSegment[]; usage STORAGE_BUFFER
  VkDeviceSize segments_size = 0;      // bytes: sizeof(StrandSegment) x segments
  VkBuffer strands = VK_NULL_HANDLE;   // StrandParameters[]; usage STORAGE_BUFFER
  VkDeviceSize strands_size = 0;       // bytes: sizeof(StrandParameters) x strands
  uint32_t segment_count = 0;
  // Segments [first_segment, first_segment + segment_count) cast (a clustered map's groom).
  uint32_t first_segment = 0;
  bool empty() const { return segment_count == 0; }
};

// Fog volumes: NanoVDB float grids marched per light texel (passes/camera/volumes/volume_pass.h
// describes the buffers: grids 32-byte aligned in one buffer, majorant bricks, and one
// GpuVolume parameter block per volume).
struct VolumeCasters {
  VkBuffer grids = VK_NULL_HANDLE;       // usage STORAGE_BUFFER
  // The majorant bricks (usage STORAGE_BUFFER); the renderer's own also hold each
  // volume's sky visibility (GpuVolume::sky_offset), which only its camera passes read.
  VkBuffer majorants = VK_NULL_HANDLE;
  VkBuffer parameters = VK_NULL_HANDLE;  // GpuVolume[]; usage STORAGE_BUFFER
  VkDeviceSize parameters_size = 0;      // bytes: sizeof(GpuVolume) x volumes
  uint32_t volume_count = 0;
  // Optional: the density brick atlas (passes/frame/volume_density_atlas.h; image in
  // SHADER_READ_ONLY_OPTIMAL, its sampler, and the brick slots, usage STORAGE_BUFFER),
  // which makes the capture several times cheaper. Without it the capture reads NanoVDB.
  VkImageView atlas = VK_NULL_HANDLE;
  VkSampler atlas_sampler = VK_NULL_HANDLE;
  VkBuffer brick_slots = VK_NULL_HANDLE;
  // Which of volumes 0..31 cast (a clustered map's); volumes from 32 on always do.
  uint32_t volume_mask = ~0u;
  bool empty() const { return volume_count == 0; }
  bool has_atlas() const { return atlas != VK_NULL_HANDLE && brick_slots != VK_NULL_HANDLE; }
};

// Everything that casts into every light's map this frame.
struct ShadowCasters {
  MeshCasters meshes;
  StrandCasters strands;
  VolumeCasters volumes;
};

}  // namespace avsm::passes
