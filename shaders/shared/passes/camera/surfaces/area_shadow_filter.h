// Push constants of the area-shadow filter (shaders/passes/camera/surfaces/area_shadow_filter.comp).
#ifndef AVSM_SHARED_PASSES_AREA_SHADOW_FILTER_H
#define AVSM_SHARED_PASSES_AREA_SHADOW_FILTER_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_AREA_SHADOW_FILTER_PUSH(F, A)                                             \
  F(mat4, inverse_view_projection)                                                    \
  F(vec4, camera_position)                                                            \
  F(uvec2, output_size)                                                               \
  F(uint, tile)            /* pixels per side whose lookups hold every virtual light */ \
  F(float, plane_tolerance) /* a neighbour counts within this share of its distance of the pixel's plane */
GPU_PUSH_CONSTANTS(AreaShadowFilterPush, GPU_AREA_SHADOW_FILTER_PUSH)

GPU_NAMESPACE_END
#endif
