#version 460
// Transmittance probes, two modes:
//  - points (mode 0): for every light and every world point, what the camera passes
//    would get from light_transmittance() there (avsm-capture --probe);
//  - texel curves (mode 1): per sample (level-0 texel, light depth, light), the
//    texel's own curve at that depth, for the light's technique and for its exact
//    reference (the capture lists, when the frame kept them; else the technique
//    again): avsm-capture --plot-texel. No filtering: the curve of that one texel,
//    what a point lookup on the texel's centre ray at that depth returns.
// Points ask paged maps for the pages they read, as the camera's receivers do, so a
// capture's probes read converged pages wherever they lie.
#extension GL_GOOGLE_include_directive : require
#define AVSM_SHADOW_BINDING 2
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 6
#include "common/shadow_lookup.glsl"

layout(local_size_x = 64) in;
// Mode 0: xyz world point. Mode 1: x, y texel, z light depth, w light index.
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
// Mode 0: [light * point_count + point]. Mode 1: [2 * sample] technique, [2 * sample + 1] reference.
layout(std430, binding = 1) writeonly buffer Results { float results[]; };
#include "shared/passes/shadows/inspection/shadow_probe.h"


void main() {
  uint point = gl_GlobalInvocationID.x;
  if (point >= pc.point_count) return;
  if (pc.mode == kProbeTexelCurves) {
    vec4 sample_ = points[point];
    uint light = uint(sample_.w);
    ivec2 texel = ivec2(sample_.xy);
    uint reference = shadows[light].reference;
    uint entries[2] = uint[2](light, reference == kNoReference ? light : reference);
    for (int i = 0; i < 2; ++i) {  // one call site: the texel lookup is compiled once
      // A paged map's curve is its finest resident level's over the texel (its reference
      // reads that page's lists; without one, kNoReference: the technique twice).
      GpuShadow s = shadows[entries[i]];
      ivec2 at = texel;
      bool held = !shadow_is_paged(s) || shadow_paged_finest_texel(shadows[entries[i]], texel, s, at);
      results[2u * point + uint(i)] = held ? shadow_texel_transmittance(s, 0u, at, sample_.z) : 1.0;
    }
    return;
  }
  if (pc.mode == kProbeSurfacePoints) {  // as the opaque pass looks surfaces up (soft kernels included)
    vec3 p = points[2u * point].xyz, n = points[2u * point + 1u].xyz;
    for (uint light = 0u; light < pc.light_count; ++light)
      results[light * pc.point_count + point] = surface_light_transmittance(light, p, n, n);
    return;
  }
  for (uint light = 0u; light < pc.light_count; ++light)
    results[light * pc.point_count + point] = light_transmittance(light, points[point].xyz);
}
