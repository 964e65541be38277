// Push constants of the timer's calibration load (spin.comp).
#ifndef AVSM_SHARED_GPU_SPIN_H
#define AVSM_SHARED_GPU_SPIN_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_SPIN_PUSH(F, A)\
  F(uint, iterations)  \
  F(uint, count)
GPU_PUSH_CONSTANTS(SpinPush, GPU_SPIN_PUSH)

GPU_NAMESPACE_END
#endif
