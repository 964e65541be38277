#version 460
// host_embed's shading pass (examples/common/ground_shading.glsl), bound through the
// engine's push descriptors by name (ShadowInputs::bind).
#extension GL_GOOGLE_include_directive : require
#define AVSM_SHADOW_BINDING 1  // any free binding: the host binds the maps by name (ShadowInputs::bind)
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 5  // paged maps: the lookups ask for pages (ShadowInputs::bind_page_requests)
layout(binding = 0, rgba16f) uniform writeonly image2D ground_image;
#include "../../common/ground_shading.glsl"
