#version 460
// The alpha-tested draws of the light depth pass: a fragment is a blocker only where
// its material lets no light through (common/caster_alpha.glsl), so masked holes and
// translucent blended texels leave the depth to what lies behind them.
#extension GL_GOOGLE_include_directive : require
#include "shared/passes/shadows/fixed_build/light_depth.h"
#define AVSM_CASTER_ALPHA_BINDING 1
#include "common/caster_alpha.glsl"

layout(location = 0) in vec2 in_uv;

void main() {
  if (caster_transmittance(in_uv) > 0.0) discard;
}
