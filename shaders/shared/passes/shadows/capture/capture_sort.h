// Push constants of the capture list sort (capture_sort.comp).
#ifndef AVSM_SHARED_PASSES_CAPTURE_SORT_H
#define AVSM_SHARED_PASSES_CAPTURE_SORT_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_CAPTURE_SORT_PUSH(F, A) F(uint, resolution)
GPU_PUSH_CONSTANTS(CaptureSortPush, GPU_CAPTURE_SORT_PUSH)

GPU_NAMESPACE_END
#endif
