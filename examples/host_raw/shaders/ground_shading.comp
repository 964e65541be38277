#version 460
// host_raw's shading pass (examples/common/ground_shading.glsl) in the host's own
// descriptor sets: its image in set 0, the shadow lookup's five buffers in set 1 at the
// bindings it chose (main.cpp's kLookupBindings says the same to the engine).
#extension GL_GOOGLE_include_directive : require
#define AVSM_SHADOW_SET 1
#define AVSM_SHADOW_PARAMETERS_BINDING 3
#define AVSM_SHADOW_ATLAS_BINDING 0
#define AVSM_SHADOW_LIST_HEADS_BINDING 5
#define AVSM_SHADOW_LIST_NODES_BINDING 1
// Paged lights: the lookups ask for the pages they read here.
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 2
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D ground_image;
#include "../../common/ground_shading.glsl"
