// Push constants of the test shader graph_fill.comp.
#ifndef AVSM_TESTS_GRAPH_FILL_H
#define AVSM_TESTS_GRAPH_FILL_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_GRAPH_FILL_PUSH(F, A) F(float, frequency) F(float, phase) F(uint, count)
GPU_PUSH_CONSTANTS(GraphFillPush, GPU_GRAPH_FILL_PUSH)

GPU_NAMESPACE_END
#endif
