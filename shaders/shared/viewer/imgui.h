// Push constants of the Dear ImGui draw lists (imgui.vert).
#ifndef AVSM_SHARED_VIEWER_IMGUI_H
#define AVSM_SHARED_VIEWER_IMGUI_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_IMGUI_PUSH(F, A)                               \
  F(vec2, scale)      /* 2 / display size */               \
  F(vec2, translate)  /* -1 - display position * scale */
GPU_PUSH_CONSTANTS(ImguiPush, GPU_IMGUI_PUSH)

GPU_NAMESPACE_END
#endif
