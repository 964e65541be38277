// Area lights with linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt,
// "Real-Time Polygonal-Light Shading with Linearly Transformed Cosines", SIGGRAPH 2016):
// the evaluation side. A lobe (the engine's GGX specular, or Lambert) is approximated by a
// clamped cosine seen through a 3x3 matrix M; its integral over a polygon is then the
// cosine's integral over the polygon's corners mapped by M^-1, which has a closed form (the
// edge sum of the polygon's projected solid angle, Lambert's formula).
//
// engine/lighting/ltc.cpp includes this file as C++ with GLM's types (the CPU integrator and
// the tests use exactly what the shader does), so keep to the common subset: no GLSL-only
// syntax (swizzles such as .xy, array constructors, out parameters), f-suffixed literals.
//
// Conventions:
//  - Positions are relative to the shading point; directions need not be unit length.
//  - A one-sided light emits on the side from which its corners run counter-clockwise,
//    the side its normal cross(p1 - p0, p3 - p0) points to.
//  - The table (engine/lighting/ltc.h) holds, per (roughness, view angle), the four
//    non-trivial coefficients (m00, m02, m20, m22) of M^-1 scaled so that m11 = 1, and the
//    lobe's magnitudes (norm, fresnel); ltc_table_uv says where an entry lies.
#ifndef AVSM_AREA_LIGHT_LTC_GLSL
#define AVSM_AREA_LIGHT_LTC_GLSL

const float kLtcPi = 3.14159265f;
// The table's first row: pbr_brdf.glsl's kPbrMinRoughness (tests/lighting checks they agree).
const float kLtcMinRoughness = 0.03f;

// The table's axes, both 0..1: x the view angle as sqrt(1 - cos theta_v), about
// theta / sqrt(2) near head-on, where the lobe's skew grows linearly with theta (ltc.h says
// why that matters); y the perceptual roughness from kLtcMinRoughness to 1.
float ltc_view_coordinate(float cos_theta_v) { return sqrt(1.0f - clamp(cos_theta_v, 0.0f, 1.0f)); }
float ltc_roughness_coordinate(float roughness) {
  return clamp((roughness - kLtcMinRoughness) / (1.0f - kLtcMinRoughness), 0.0f, 1.0f);
}

// Texture coordinates of a size x size table (entry centres at the ends), for bilinear
// filtering: x the view angle, y the roughness.
vec2 ltc_table_uv(float roughness, float cos_theta_v, float table_size) {
  vec2 coordinate = vec2(ltc_view_coordinate(cos_theta_v), ltc_roughness_coordinate(roughness));
  return (coordinate * (table_size - 1.0f) + vec2(0.5f)) / table_size;
}

// M^-1 from a table entry's coefficients (m00, m02, m20, m22); m11 = 1.
mat3 ltc_inverse_matrix(vec4 m) {
  return mat3(vec3(m.x, 0.0f, m.z), vec3(0.0f, 1.0f, 0.0f), vec3(m.y, 0.0f, m.w));
}

// A unit vector perpendicular to n.
vec3 ltc_any_tangent(vec3 n) {
  return abs(n.x) < 0.9f ? normalize(cross(n, vec3(1.0f, 0.0f, 0.0f))) : normalize(cross(n, vec3(0.0f, 1.0f, 0.0f)));
}

// World to the shading frame the table was fitted in: z the normal, x towards the viewer
// (v's part along the surface), so that the lobe is symmetric about the xz plane. Seen
// head on the lobe is round and any tangent does.
mat3 ltc_shading_frame(vec3 n, vec3 v) {
  vec3 along_surface = v - n * dot(n, v);
  float length2 = dot(along_surface, along_surface);
  vec3 tangent = length2 > 1e-12f ? along_surface / sqrt(length2) : ltc_any_tangent(n);
  vec3 bitangent = cross(n, tangent);
  return transpose(mat3(tangent, bitangent, n));
}

// The edge a -> b's term of the polygon's projected solid angle, times 2 pi: the angle the
// edge subtends times the z component of its great circle's normal. Oriented so that a
// polygon running counter-clockwise seen from the origin counts positive. atan rather
// than acos keeps short edges (small or distant lights) accurate in float.
float ltc_edge_integral(vec3 a, vec3 b) {
  vec3 from = normalize(a);
  vec3 to = normalize(b);
  vec3 normal = cross(to, from);
  float sin_angle = length(normal);
  float angle = atan(sin_angle, dot(from, to));
  return normal.z * (sin_angle > 1e-7f ? angle / sin_angle : 1.0f);
}

// Where the segment a -> b crosses the horizon z = 0 (a and b on either side of it).
vec3 ltc_horizon_crossing(vec3 a, vec3 b) { return mix(a, b, a.z / (a.z - b.z)); }

// The edge a -> b's term once the polygon is clipped to the upper hemisphere (z > 0), where
// the clamped cosine lives: the part of the edge above the horizon.
float ltc_clipped_edge_integral(vec3 a, vec3 b) {
  bool a_above = a.z > 0.0f;
  bool b_above = b.z > 0.0f;
  if (a_above && b_above) return ltc_edge_integral(a, b);
  if (a_above) return ltc_edge_integral(a, ltc_horizon_crossing(a, b));
  if (b_above) return ltc_edge_integral(ltc_horizon_crossing(a, b), b);
  return 0.0f;
}

// Where the polygon leaves (exit) or comes back above (entry) the horizon on the edge a -> b,
// or a zero vector. A convex polygon has at most one of each, so the sum over its edges is
// that point: clipping then needs no list of clipped corners.
vec3 ltc_exit_point(vec3 a, vec3 b) { return (a.z > 0.0f && b.z <= 0.0f) ? ltc_horizon_crossing(a, b) : vec3(0.0f); }
vec3 ltc_entry_point(vec3 a, vec3 b) { return (a.z <= 0.0f && b.z > 0.0f) ? ltc_horizon_crossing(a, b) : vec3(0.0f); }

// The clipped polygon's closing edge along the horizon, from its exit to its entry point;
// 0 when the polygon does not cross the horizon (both points zero).
float ltc_horizon_edge_integral(vec3 exit_point, vec3 entry_point) {
  bool crosses = dot(exit_point, exit_point) > 0.0f && dot(entry_point, entry_point) > 0.0f;
  return crosses ? ltc_edge_integral(exit_point, entry_point) : 0.0f;
}

// The clamped cosine's integral (max(z, 0) / pi over the sphere, 1 in all) over the convex
// quad q0 q1 q2 q3, corners already in the cosine's space. Signed: positive when the corners
// run counter-clockwise seen from the origin (its lit side faces the shading point).
float ltc_quad_integral(vec3 q0, vec3 q1, vec3 q2, vec3 q3) {
  float sum = ltc_clipped_edge_integral(q0, q1) + ltc_clipped_edge_integral(q1, q2) +
              ltc_clipped_edge_integral(q2, q3) + ltc_clipped_edge_integral(q3, q0);
  vec3 exit_point = ltc_exit_point(q0, q1) + ltc_exit_point(q1, q2) + ltc_exit_point(q2, q3) + ltc_exit_point(q3, q0);
  vec3 entry_point =
      ltc_entry_point(q0, q1) + ltc_entry_point(q1, q2) + ltc_entry_point(q2, q3) + ltc_entry_point(q3, q0);
  sum += ltc_horizon_edge_integral(exit_point, entry_point);
  return sum / (2.0f * kLtcPi);
}

// A rectangle light's share of a lobe: the lobe's integral over the rectangle p0 p1 p2 p3
// (corners relative to the shading point), without the lobe's magnitude. to_cosine maps
// world directions into the cosine's space: ltc_inverse_matrix(entry) * ltc_shading_frame(n, v)
// for GGX, ltc_shading_frame(n, v) alone for Lambert (exact: Lambert is a clamped cosine).
// Times the magnitude this is the integral of BRDF x cos over the light.
float ltc_rect_integral(mat3 to_cosine, vec3 p0, vec3 p1, vec3 p2, vec3 p3, bool two_sided) {
  float signed_integral = ltc_quad_integral(to_cosine * p0, to_cosine * p1, to_cosine * p2, to_cosine * p3);
  return two_sided ? abs(signed_integral) : max(signed_integral, 0.0f);
}

// A disk light's share of a lobe, as ltc_rect_integral's: the disk (centre relative to the
// shading point, radius, emitting along cross(t1, t2)) as a regular polygon of
// kLtcShaderDiskEdges edges with the disk's area. Each edge's corners are mapped as they
// come, and the horizon is crossed at most once each way (the polygon is convex), so the
// clipping needs no list of corners.
const int kLtcShaderDiskEdges = 16;
float ltc_disk_integral(mat3 to_cosine, vec3 centre, vec3 t1, vec3 t2, float radius, bool two_sided) {
  float wedge = 2.0f * kLtcPi / float(kLtcShaderDiskEdges);
  // An inscribed regular polygon has less area than its circle; this radius gives it the same.
  float polygon_radius = radius * sqrt(wedge / sin(wedge));
  vec3 first = to_cosine * (centre + polygon_radius * t1);
  vec3 previous = first;
  float sum = 0.0f;
  vec3 exit_point = vec3(0.0f);
  vec3 entry_point = vec3(0.0f);
  for (int k = 1; k <= kLtcShaderDiskEdges; ++k) {
    float angle = wedge * float(k);
    vec3 current = k == kLtcShaderDiskEdges
                       ? first
                       : to_cosine * (centre + polygon_radius * (cos(angle) * t1 + sin(angle) * t2));
    sum += ltc_clipped_edge_integral(previous, current);
    exit_point += ltc_exit_point(previous, current);
    entry_point += ltc_entry_point(previous, current);
    previous = current;
  }
  sum += ltc_horizon_edge_integral(exit_point, entry_point);
  float signed_integral = sum / (2.0f * kLtcPi);
  return two_sided ? abs(signed_integral) : max(signed_integral, 0.0f);
}

// A sphere light's share: the disk of its silhouette (where the cone from the shading point
// touches it), which subtends the same solid angle, facing the point. Inside it: the whole lobe.
float ltc_sphere_integral(mat3 to_cosine, vec3 centre, float radius) {
  float distance = length(centre);
  if (distance <= radius) return 1.0f;
  float ratio = radius / distance;
  vec3 towards_point = -centre / distance;
  vec3 t1 = ltc_any_tangent(towards_point);
  vec3 t2 = cross(towards_point, t1);
  return ltc_disk_integral(to_cosine, centre + towards_point * (radius * ratio), t1, t2,
                           radius * sqrt(1.0f - ratio * ratio), false);
}

// The GGX lobe's magnitude with Schlick's Fresnel from a table entry's (norm, fresnel):
// the integral of D V F cos over the sphere is F0 norm + (1 - F0) fresnel.
vec3 ltc_specular_magnitude(float norm, float fresnel, vec3 f0) { return f0 * (norm - fresnel) + vec3(fresnel); }

#endif
