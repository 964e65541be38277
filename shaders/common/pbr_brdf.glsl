// glTF 2.0's metallic-roughness BRDF (the specification's Appendix B), written once for
// GLSL and C++: GGX normal distribution, Smith height-correlated visibility and
// Schlick's Fresnel for the specular lobe; F0 = mix(0.04, base colour, metallic) and a
// Lambert diffuse of (1 - F) x base colour x (1 - metallic) / pi.
//
// Light units. The engine's lights (light_radiance in lights.glsl) and its sky
// (kSkyAmbient) are given as the radiance a white Lambertian surface reflects when it
// faces them, so a light's irradiance is pi times that: the reflected radiance is
// pi x f(l, v) x light x (n . l), and a Lambert-white surface head-on gives the light's
// value back, as it did before this BRDF.
//
// C++ includes this file through passes/camera/surfaces/pbr_brdf.h, which brings GLSL's types and
// built-ins in from GLM. Keep to the common subset: no GLSL-only syntax (swizzles
// such as .zw, constructors of structs), float literals with an f suffix.
#ifndef AVSM_PBR_BRDF_GLSL
#define AVSM_PBR_BRDF_GLSL

const float kPbrPi = 3.14159265f;
// Below this perceptual roughness GGX is a spike no pixel resolves (and at 0 it
// divides by zero); alpha = roughness^2 as glTF defines it.
const float kPbrMinRoughness = 0.03f;

// A surface point's material after its textures: linear base colour, metallic and
// perceptual roughness in 0..1.
struct PbrSurface {
  vec3 base_color;
  float metallic;
  float roughness;
};

vec3 pbr_f0(PbrSurface s) { return mix(vec3(0.04f), s.base_color, s.metallic); }

float pbr_alpha(float roughness) {
  float r = clamp(roughness, kPbrMinRoughness, 1.0f);
  return r * r;
}

// GGX / Trowbridge-Reitz microfacet distribution D.
float pbr_ggx_distribution(float n_dot_h, float alpha) {
  float a2 = alpha * alpha;
  float d = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPbrPi * d * d);
}

// Smith's height-correlated masking-shadowing over 4 (n . l)(n . v): V = G / (4 |n.l| |n.v|).
float pbr_smith_visibility(float n_dot_l, float n_dot_v, float alpha) {
  float a2 = alpha * alpha;
  float towards_view = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2);
  float towards_light = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2);
  return 0.5f / max(towards_view + towards_light, 1e-7f);
}

vec3 pbr_schlick_fresnel(vec3 f0, float v_dot_h) {
  float x = clamp(1.0f - v_dot_h, 0.0f, 1.0f);
  float x2 = x * x;
  return f0 + (vec3(1.0f) - f0) * (x2 * x2 * x);
}

// f(l, v): n, v and l unit vectors, l above the surface (n . l > 0). A normal that a
// normal texture turned away from the viewer is treated as grazing.
vec3 pbr_brdf(PbrSurface s, vec3 n, vec3 v, vec3 l) {
  vec3 h = normalize(l + v);
  float n_dot_l = clamp(dot(n, l), 0.0f, 1.0f);
  float n_dot_v = clamp(dot(n, v), 1e-4f, 1.0f);
  float n_dot_h = clamp(dot(n, h), 0.0f, 1.0f);
  float v_dot_h = clamp(dot(v, h), 0.0f, 1.0f);
  float alpha = pbr_alpha(s.roughness);
  vec3 fresnel = pbr_schlick_fresnel(pbr_f0(s), v_dot_h);
  vec3 specular = fresnel * (pbr_ggx_distribution(n_dot_h, alpha) * pbr_smith_visibility(n_dot_l, n_dot_v, alpha));
  vec3 diffuse = (vec3(1.0f) - fresnel) * s.base_color * ((1.0f - s.metallic) / kPbrPi);
  return diffuse + specular;
}

// Radiance towards v from one light of value `light` (see "Light units" above).
vec3 pbr_direct(PbrSurface s, vec3 n, vec3 v, vec3 l, vec3 light) {
  return pbr_brdf(s, n, v, l) * light * (kPbrPi * clamp(dot(n, l), 0.0f, 1.0f));
}

// Radiance towards v from a uniform sky of radiance `sky`, scaled by ambient occlusion:
// the diffuse part exactly (base colour x (1 - metallic) x sky), the specular part
// with Karis's analytic fit of GGX's directional albedo, F0 x A + B ("Physically Based
// Shading on Mobile", 2014).
vec3 pbr_sky(PbrSurface s, float n_dot_v, vec3 sky, float occlusion) {
  vec4 r = clamp(s.roughness, kPbrMinRoughness, 1.0f) * vec4(-1.0f, -0.0275f, -0.572f, 0.022f) +
           vec4(1.0f, 0.0425f, 1.04f, -0.04f);
  float a004 = min(r.x * r.x, exp2(-9.28f * clamp(n_dot_v, 0.0f, 1.0f))) * r.x + r.y;
  vec2 scale_bias = vec2(-1.04f, 1.04f) * a004 + vec2(r.z, r.w);
  vec3 specular = pbr_f0(s) * scale_bias.x + vec3(scale_bias.y);
  vec3 diffuse = s.base_color * (1.0f - s.metallic);
  return (diffuse + specular) * sky * occlusion;
}

#endif
