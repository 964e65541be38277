// A push-constant block written once whose C++ and GLSL layouts still differ: a vec3
// after a float sits at byte 16 in GLSL (std430 aligns it to 16) and at byte 4 in
// C++ (GLM's vec3 aligns to 4). tests/gpu/interface_check_test.cpp expects pipeline
// creation to catch it.
#ifndef AVSM_TESTS_MISALIGNED_H
#define AVSM_TESTS_MISALIGNED_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_MISALIGNED_PUSH(F, A) F(float, scale) F(vec3, direction)
GPU_PUSH_CONSTANTS(MisalignedPush, GPU_MISALIGNED_PUSH)

GPU_NAMESPACE_END
#endif
