// The constant debug technique's lookup (constant.cpp): the transmittance it was given.
#ifndef AVSM_TECHNIQUE_CONSTANT_GLSL
#define AVSM_TECHNIQUE_CONSTANT_GLSL

float constant_lookup(GpuShadow s, uint level, ivec2 texel, float d) { return s.technique_data.x; }

#endif
