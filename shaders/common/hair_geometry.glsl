// Hair ribbon geometry, written once for GLSL and C++: a strand segment's ribbon
// turned towards a point (the quad common/hair_ribbon.glsl draws), and that ribbon as
// a light's rasterizer sees it (common/hair_footprint.glsl: the hair binning and the
// fixed-memory build cover light texels with it themselves). Pure functions of the
// segment's two points, its strand's width and opacity: the includers read the buffers.
//
// C++ includes this file through passes/frame/hair_geometry.h, which defines AVSM_OUT and
// brings GLSL's types and built-ins in from GLM, so tests can reproduce the GPU's
// coverage and depths on the CPU with the same arithmetic. Keep to the common subset:
// no swizzles, no array constructors, float literals with an f suffix, out
// parameters through AVSM_OUT.
#ifndef AVSM_HAIR_GEOMETRY_GLSL
#define AVSM_HAIR_GEOMETRY_GLSL

#ifndef AVSM_OUT
#define AVSM_OUT(T) out T
#endif

// A ribbon quad is 6 corners (two triangles): (p0, -side), (p1, -side), (p1, +side),
// (p0, -side), (p1, +side), (p0, +side).
uint hair_ribbon_corner_along(uint corner) { return (corner == 1u || corner == 2u || corner == 4u) ? 1u : 0u; }
float hair_ribbon_corner_side(uint corner) { return (corner == 2u || corner >= 4u) ? 1.0f : -1.0f; }

struct RibbonCorner {
  vec3 world;
  vec3 tangent;
  float opacity;  // the strand's, scaled by the widening
};

// Ribbons are kept at least one pixel wide, their opacity scaled by the widening
// (coverage), so thin strands keep their weight instead of flickering.
RibbonCorner hair_ribbon_corner(vec3 p0, vec3 p1, float width, float opacity, uint corner, mat4 view_projection,
                                vec3 facing_point, vec2 viewport) {
  vec3 p = hair_ribbon_corner_along(corner) == 0u ? p0 : p1;
  vec3 tangent = normalize(p1 - p0 + vec3(1e-9f));
  vec3 to_facing = normalize(facing_point - p);
  vec3 side = normalize(cross(tangent, to_facing) + vec3(1e-9f));

  vec4 clip_center = view_projection * vec4(p, 1.0f);
  vec4 clip_offset = view_projection * vec4(p + side * width, 1.0f);
  vec2 pixels = abs(vec2(clip_offset.x, clip_offset.y) / clip_offset.w - vec2(clip_center.x, clip_center.y) / clip_center.w) *
                0.5f * viewport;
  float width_pixels = max(length(pixels), 1e-6f);
  float widen = max(1.0f, 1.0f / width_pixels);

  RibbonCorner v;
  v.world = p + side * (0.5f * width * widen * hair_ribbon_corner_side(corner));
  v.tangent = tangent;
  v.opacity = opacity / widen;
  return v;
}

// ---- The ribbon as a light's rasterizer sees it ----
// Coverage follows the rasterizer: a texel centre inside one of the quad's two
// triangles (0, 1, 2) and (0, 2, 3), its depth interpolated perspective-correctly, the
// opacity of the provoking (first) corner.

struct HairFootprint {
  vec4 x, y;         // corners in texels: (p0, -side), (p1, -side), (p1, +side), (p0, +side)
  vec4 depth;        // their light depths
  vec4 inverse_w;    // 1 / clip w, for perspective-correct interpolation
  float opacity;     // per crossing, scaled down by the widening to one texel
  bool valid;        // every corner in front of the light
};

// The footprint of the ribbon from p0 to p1 (its strand's width and opacity) in a
// resolution^2 map seen through view_projection, ribbons facing facing_point.
HairFootprint hair_footprint_of(vec3 p0, vec3 p1, float width, float opacity, mat4 view_projection,
                                vec3 facing_point, vec4 depth_plane, float resolution) {
  HairFootprint f;
  f.valid = true;
  f.opacity = 0.0f;
  for (int k = 0; k < 4; ++k) {
    uint corner = k == 3 ? 5u : uint(k);  // the quad's corners among the 6
    RibbonCorner v = hair_ribbon_corner(p0, p1, width, opacity, corner, view_projection, facing_point, vec2(resolution));
    vec4 clip = view_projection * vec4(v.world, 1.0f);
    f.valid = f.valid && clip.w > 0.0f;
    vec2 texel = (vec2(clip.x, clip.y) / clip.w * 0.5f + 0.5f) * resolution;
    f.x[k] = texel.x;
    f.y[k] = texel.y;
    f.depth[k] = dot(vec3(depth_plane), v.world) + depth_plane.w;
    f.inverse_w[k] = 1.0f / clip.w;
    if (k == 0) f.opacity = clamp(v.opacity, 0.0f, 1.0f);
  }
  return f;
}

// Twice the signed area of (a, b, p).
float footprint_edge(vec2 a, vec2 b, vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Whether point p lies in triangle (a, b, c) of either winding; its barycentrics if so.
bool footprint_triangle(vec2 a, vec2 b, vec2 c, vec2 p, AVSM_OUT(vec3) weights) {
  float area = footprint_edge(a, b, c);
  weights = vec3(footprint_edge(b, c, p), footprint_edge(c, a, p), footprint_edge(a, b, p)) / area;
  return area != 0.0f && all(greaterThanEqual(weights, vec3(0.0f)));
}

// Whether the ribbon covers point p (texels); its light depth there if so.
bool hair_footprint_covers(HairFootprint f, vec2 p, AVSM_OUT(float) depth) {
  vec2 c0 = vec2(f.x[0], f.y[0]), c1 = vec2(f.x[1], f.y[1]), c2 = vec2(f.x[2], f.y[2]), c3 = vec2(f.x[3], f.y[3]);
  vec3 w;
  vec3 d, iw;
  if (footprint_triangle(c0, c1, c2, p, w)) {
    d = vec3(f.depth.x, f.depth.y, f.depth.z);
    iw = vec3(f.inverse_w.x, f.inverse_w.y, f.inverse_w.z);
  } else if (footprint_triangle(c0, c2, c3, p, w)) {
    d = vec3(f.depth.x, f.depth.z, f.depth.w);
    iw = vec3(f.inverse_w.x, f.inverse_w.z, f.inverse_w.w);
  } else {
    depth = 0.0f;
    return false;
  }
  vec3 perspective = w * iw;
  depth = dot(perspective, d) / dot(perspective, vec3(1.0f));
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
  lo = clamp(lo, vec2(-1.0f), vec2(float(resolution) + 1.0f));
  hi = clamp(hi, vec2(-1.0f), vec2(float(resolution) + 1.0f));
  ivec2 first = ivec2(ceil(lo - 0.5f)), last = ivec2(floor(hi - 0.5f));
  first = max(first, ivec2(0));
  last = min(last, ivec2(resolution - 1));
  return ivec4(first, last);
}

#endif
