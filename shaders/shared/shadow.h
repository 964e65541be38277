// What a camera pass reads to look a light's shadows up (shaders/common/shadow_lookup.glsl):
// GpuShadow records (one per scene light first, then the extra maps of lights with
// several), every map in one atlas buffer at its record's map_offset, and for lookups
// that read capture lists (the exact reference) the lists in two more buffers, also
// at per-record offsets. No per-light descriptors, so no cap on the number of lights.
#ifndef AVSM_SHARED_SHADOW_H
#define AVSM_SHARED_SHADOW_H
#include "shared/gpu_struct.h"
#include "shared/pages.h"
GPU_NAMESPACE_BEGIN

// GpuShadow::technique: a light without shadows; the techniques' codes follow their
// registry order from 1 (passes/shadows/techniques/registry.h).
GPU_CONST(uint, kShadowNone, 0u)
// GpuShadow::filter_mode
GPU_CONST(uint, kFilterPoint, 0u)
GPU_CONST(uint, kFilterBilinear, 1u)
GPU_CONST(uint, kFilterTrilinear, 2u)
// GpuShadow::reference when the light has no exact-reference entry
GPU_CONST(uint, kNoReference, 0xffffffffu)
// GpuShadow::kernel: surface lookups filtered over a kernel of texel curves (soft
// shadow edges); volume and hair lookups stay bilinear (they run per march step).
GPU_CONST(uint, kKernelNone, 0u)
GPU_CONST(uint, kKernelBox, 1u)       // a box 2r + 1 texels wide, each texel weighted by its overlap
GPU_CONST(uint, kKernelGaussian, 2u)  // a Gaussian of sigma r / 2 over the same taps
GPU_CONST(uint, kMaxKernelRadius, 4u)
// GpuShadow::views: how a light's record finds its maps.
GPU_CONST(uint, kViewsSingle, 0u)    // the record is the light's one map
GPU_CONST(uint, kViewsCube, 1u)      // a point light: six face maps, +x -x +y -y +z -z
GPU_CONST(uint, kViewsCascades, 2u)  // a directional light split along the camera's view
GPU_CONST(uint, kViewsClusters, 3u)  // one map per caster cluster; transmittances multiply
GPU_CONST(uint, kViewsVirtualLights, 4u)  // an area light: one map per virtual light; transmittances average
// The most maps one light has (cube faces, cascades, clusters or virtual lights): the
// lookup loops to it.
GPU_CONST(uint, kMaxViewsPerLight, 256u)
GPU_CONST(uint, kMaxClustersPerLight, 8u)

#define GPU_SHADOW(F, A)                                                                                        \
  F(mat4, light_from_world) /* world -> light clip; uv = clip.xy / clip.w * 0.5 + 0.5 */                       \
  F(vec4, depth_plane)      /* light depth(p) = dot(xyz, p) + w */                                             \
  F(vec4, texel_camera)     /* x, y: level-0 texel world size = x + y * depth; z: far depth;                   \
                               w: camera radians per pixel */                                                  \
  F(vec4, camera_position)  /* xyz; w: receivers' normal offset in texels */                                   \
  F(vec4, depth_range)      /* x, y: the light's caster depth range (osm and fom normalise over it);           \
                               z: osm/fom lookup bias (depth units), against self-shadowing inside a slice */  \
  F(vec4, technique_data)   /* the technique's own lookup numbers (constant: x, its transmittance) */          \
  F(vec4, view_select)      /* cube: xyz the light's position; cascades: xyz the camera's forward axis,        \
                               w the fraction of a split blended into the next */                             \
  F(vec4, cascade_ends)     /* cascades: camera depth where split 0..3 ends */                                 \
  F(uint, technique)        /* kShadowNone, or the technique's registry code */                                \
  F(uint, node_count)       /* avsm: N nodes (a multiple of 4); osm: K planes; fom: K terms */                 \
  F(uint, resolution)       /* level-0 texels per side */                                                      \
  F(uint, mip_count)                                                                                           \
  F(uint, filter_mode)      /* kFilter* */                                                                     \
  F(uint, exponential)      /* 1: exponential interpolation between nodes */                                   \
  F(uint, map_offset)       /* the map's first vec4 in the atlas (ShadowMapAtlas) */                           \
  F(uint, list_heads_offset) /* its capture lists' first head in ShadowListHeads (lookups that read lists) */   \
  F(uint, list_nodes_offset) /* and first node in ShadowListNodes */                                           \
  F(uint, reference)        /* index of this record's exact-reference record in shadows[], or kNoReference */  \
  F(uint, views)            /* kViews*: a light's record; the maps' own records are kViewsSingle */            \
  F(uint, first_view)       /* kViewsCube..VirtualLights: the light's maps are records first_view ..         \
                               first_view + view_count - 1 */                                                  \
  F(uint, view_count)                                                                                          \
  F(uint, kernel)           /* kKernel*: the soft-shadow kernel of surface lookups */                          \
  F(uint, kernel_radius)    /* its radius in level-0 texels, 1 to kMaxKernelRadius */                         \
  F(float, page_volume_lod_bias) /* paged: levels added to smoke receivers' on top of page_lod_bias */      \
  F(uint, page_size)        /* kDenseLayout, or a paged map's page texels per side (shared/pages.h); then  \
                               resolution is the virtual one, mip_count its levels and map_offset its      \
                               page table */                                                                \
  F(uint, page_pool_offset) /* paged: the pool's first vec4 in the atlas */                                \
  F(uint, page_requests_offset) /* paged: its request bits' first word, or kNoPageRequests */              \
  F(float, page_lod_bias)   /* paged: levels added to every receiver's (coarser when > 0) */                 \
  F(uint, page_fallback_level) /* paged: the coarsest level receivers ask for (passes/shadows/shadow_settings.h) */ \
  F(uint, page_window)      /* paged: pages per side of a clipmap level's window, 0: whole levels */        \
  F(uvec2, page_window_centre) /* paged: the level-0 texel the windows are centred on (the camera's) */      \
  F(uint, page_slot_nodes)  /* paged lists (uncompressed): capture segments per slot of the light's pool */   \
  F(uint, padding1)                                                                                          \
  F(uint, padding2)                                                                                          \
  F(uint, padding3)
GPU_STRUCT(GpuShadow, GPU_SHADOW)

GPU_NAMESPACE_END
#endif
