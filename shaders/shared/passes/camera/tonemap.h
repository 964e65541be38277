// Push constants of the HDR-to-display pass (tonemap.comp).
#ifndef AVSM_SHARED_PASSES_TONEMAP_H
#define AVSM_SHARED_PASSES_TONEMAP_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_TONEMAP_PUSH(F, A) F(float, exposure)
GPU_PUSH_CONSTANTS(TonemapPush, GPU_TONEMAP_PUSH)

GPU_NAMESPACE_END
#endif
