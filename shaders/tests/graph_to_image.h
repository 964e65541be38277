// Push constants of the test shader graph_to_image.comp.
#ifndef AVSM_TESTS_GRAPH_TO_IMAGE_H
#define AVSM_TESTS_GRAPH_TO_IMAGE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_GRAPH_TO_IMAGE_PUSH(F, A) F(vec4, tint) F(uint, width) F(uint, height)
GPU_PUSH_CONSTANTS(GraphToImagePush, GPU_GRAPH_TO_IMAGE_PUSH)

GPU_NAMESPACE_END
#endif
