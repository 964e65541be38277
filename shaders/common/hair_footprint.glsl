// A hair segment's ribbon as a light's rasterizer sees it (the quad of
// common/hair_ribbon.glsl that capture_hair.vert draws facing the light), for the
// passes that cover light texels with it themselves: the hair binning and the
// fixed-memory AVSM build. Coverage follows the rasterizer: a texel centre inside
// one of the quad's two triangles (0, 1, 2) and (0, 2, 3), its depth interpolated
// perspective-correctly, the opacity of the provoking (first) corner.
#ifndef AVSM_HAIR_FOOTPRINT_GLSL
#define AVSM_HAIR_FOOTPRINT_GLSL
#extension GL_GOOGLE_include_directive : require
#include "common/hair_ribbon.glsl"

struct HairFootprint {
  vec4 x, y;         // corners in texels: (p0, -side), (p1, -side), (p1, +side), (p0, +side)
  vec4 depth;        // their light depths
  vec4 inverse_w;    // 1 / clip w, for perspective-correct interpolation
  float opacity;     // per crossing, scaled down by the widening to one texel
  bool valid;        // every corner in front of the light
};

HairFootprint hair_footprint(uint segment, mat4 view_projection, vec3 facing_point, vec4 depth_plane,
                             float resolution) {
  const uint kCorner[4] = uint[](0u, 1u, 2u, 5u);  // hair_ribbon_vertex corners of the quad
  HairFootprint f;
  f.valid = true;
  for (int k = 0; k < 4; ++k) {
    RibbonVertex v = hair_ribbon_vertex(6u * segment + kCorner[k], view_projection, facing_point, vec2(resolution));
    vec4 clip = view_projection * vec4(v.world, 1.0);
    f.valid = f.valid && clip.w > 0.0;
    vec2 texel = (clip.xy / clip.w * 0.5 + 0.5) * resolution;
    f.x[k] = texel.x;
    f.y[k] = texel.y;
    f.depth[k] = dot(depth_plane.xyz, v.world) + depth_plane.w;
    f.inverse_w[k] = 1.0 / clip.w;
    if (k == 0) f.opacity = clamp(v.color_opacity.a, 0.0, 1.0);
  }
  return f;
}

// Twice the signed area of (a, b, p).
float footprint_edge(vec2 a, vec2 b, vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Whether point p lies in triangle (a, b, c) of either winding; its barycentrics if so.
bool footprint_triangle(vec2 a, vec2 b, vec2 c, vec2 p, out vec3 weights) {
  float area = footprint_edge(a, b, c);
  weights = vec3(footprint_edge(b, c, p), footprint_edge(c, a, p), footprint_edge(a, b, p)) / area;
  return area != 0.0 && all(greaterThanEqual(weights, vec3(0.0)));
}

// Whether the ribbon covers point p (texels); its light depth there if so.
bool hair_footprint_covers(HairFootprint f, vec2 p, out float depth) {
  vec2 c0 = vec2(f.x[0], f.y[0]), c1 = vec2(f.x[1], f.y[1]), c2 = vec2(f.x[2], f.y[2]), c3 = vec2(f.x[3], f.y[3]);
  vec3 w;
  vec3 d, iw;
  if (footprint_triangle(c0, c1, c2, p, w)) {
    d = f.depth.xyz;
    iw = f.inverse_w.xyz;
  } else if (footprint_triangle(c0, c2, c3, p, w)) {
    d = vec3(f.depth.x, f.depth.z, f.depth.w);
    iw = vec3(f.inverse_w.x, f.inverse_w.z, f.inverse_w.w);
  } else {
    depth = 0.0;
    return false;
  }
  vec3 perspective = w * iw;
  depth = dot(perspective, d) / dot(perspective, vec3(1.0));
  return true;
}

// The ribbon's texel bounding box, clamped to the map: (min x, min y, max x, max y),
// empty (max < min) when it misses the map or lies behind the light.
ivec4 hair_footprint_texels(HairFootprint f, int resolution) {
  if (!f.valid) return ivec4(0, 0, -1, -1);
  vec2 lo = vec2(min(min(f.x[0], f.x[1]), min(f.x[2], f.x[3])), min(min(f.y[0], f.y[1]), min(f.y[2], f.y[3])));
  vec2 hi = vec2(max(max(f.x[0], f.x[1]), max(f.x[2], f.x[3])), max(max(f.y[0], f.y[1]), max(f.y[2], f.y[3])));
  // Texel t's centre is t + 0.5: the texels whose centres the box can hold (clamped
  // first, so a corner near the light's plane cannot overflow the conversion).
  lo = clamp(lo, vec2(-1.0), vec2(float(resolution) + 1.0));
  hi = clamp(hi, vec2(-1.0), vec2(float(resolution) + 1.0));
  ivec2 first = ivec2(ceil(lo - 0.5)), last = ivec2(floor(hi - 0.5));
  first = max(first, ivec2(0));
  last = min(last, ivec2(resolution - 1));
  return ivec4(first, last);
}

#endif
