// Push constants of the test shader fill.comp.
#ifndef AVSM_TESTS_FILL_H
#define AVSM_TESTS_FILL_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_FILL_PUSH(F, A) F(float, scale) F(float, offset) F(uint, count)
GPU_PUSH_CONSTANTS(FillPush, GPU_FILL_PUSH)

GPU_NAMESPACE_END
#endif
