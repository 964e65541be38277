#version 460
// Hair fragments, fast path: the lighting comes per vertex (hair_lighting.comp), and
// the fragment is seen through the smoke in front of it: premultiplied a * (S + T *
// colour), blended over the colour the smoke was already composited into, which is
// exact for one layer. No shadow lookup is compiled in here (on lavapipe their mere
// presence slows a shader); hair_reference.frag lights per fragment.
layout(location = 2) flat in vec4 in_color_opacity;
layout(location = 3) in vec3 in_lit;
layout(location = 4) in vec4 in_fog;
layout(location = 0) out vec4 out_color;

void main() {
  float a = in_color_opacity.a;
  out_color = vec4(a * (in_fog.rgb + in_fog.a * in_color_opacity.rgb * in_lit), a);  // premultiplied
}
