// Hair strands as the shaders read them (shaders/common/hair_ribbon.glsl): a strand
// is a polyline of points (vec4, xyz world); each segment joins `first_point` and the
// next point. Per strand vertex, hair_lighting.comp writes one HairVertexLight.
#ifndef AVSM_SHARED_HAIR_H
#define AVSM_SHARED_HAIR_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_STRAND_SEGMENT(F, A) F(uint, first_point) F(uint, strand)
GPU_STRUCT(StrandSegment, GPU_STRAND_SEGMENT)

#define GPU_STRAND(F, A)                                                                             \
  F(vec4, color_opacity) /* a: opacity per strand crossing; the capture stores 1 - opacity */       \
  F(float, width)        /* world units (ribbons are widened to a pixel, their opacity scaled down) */ \
  A(float, pad, 3)
GPU_STRUCT(Strand, GPU_STRAND)

#define GPU_HAIR_VERTEX_LIGHT(F, A)                                                             \
  F(vec4, lit) /* rgb: light reaching the fibre (sky included), times the strand colour later */ \
  F(vec4, fog) /* rgb: smoke in-scattering between the camera and the vertex; a: its transmittance */
GPU_STRUCT(HairVertexLight, GPU_HAIR_VERTEX_LIGHT)

GPU_NAMESPACE_END
#endif
