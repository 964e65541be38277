// How much light a mesh caster lets through at a fragment, from its material's alpha
// (passes/frame/caster_alpha.h; shared/mesh.h's kCasterAlpha* modes): opaque 0; mask 0 where
// the alpha reaches the cutoff, else 1; blend 1 - alpha. Alpha is the base colour
// factor's times the base-colour texture's at the caster's uv.
// Before including: the push block `pc` with GPU_CASTER_ALPHA_PUSH's members, and
// AVSM_CASTER_ALPHA_BINDING, the texture's binding.
#ifndef AVSM_CASTER_ALPHA_GLSL
#define AVSM_CASTER_ALPHA_GLSL

layout(binding = AVSM_CASTER_ALPHA_BINDING) uniform sampler2D base_color_texture;

float caster_transmittance(vec2 uv) {
  if (pc.alpha_mode == kCasterAlphaOpaque) return 0.0;  // no texture fetch for opaque draws
  float alpha = pc.alpha_factor * texture(base_color_texture, uv).a;
  if (pc.alpha_mode == kCasterAlphaMask) return alpha >= pc.alpha_cutoff ? 0.0 : 1.0;
  return clamp(1.0 - alpha, 0.0, 1.0);
}

#endif
