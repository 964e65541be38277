// Push constants of the shadow level overlay (shadow_level_overlay.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_LEVEL_OVERLAY_H
#define AVSM_SHARED_PASSES_SHADOW_LEVEL_OVERLAY_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_SHADOW_LEVEL_OVERLAY_PUSH(F, A) \
  F(uvec2, image_size)                      \
  F(uint, light)  /* whose levels are shown */
GPU_PUSH_CONSTANTS(ShadowLevelOverlayPush, GPU_SHADOW_LEVEL_OVERLAY_PUSH)

// How many levels have a colour of their own (shadow_level_colour()); coarser ones take the last.
GPU_CONST(uint, kOverlayLevelColours, 8u)

GPU_NAMESPACE_END
#endif
