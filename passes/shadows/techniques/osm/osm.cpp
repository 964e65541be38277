// Opacity shadow maps (Kim & Neumann 2001): K planes of accumulated optical depth over
// the light's caster depth range (osm_build.comp, K floats per texel).
#include "passes/shadows/techniques/opacity_map_technique.h"

namespace avsm::passes {
namespace {

constexpr TechniqueParameter kOsmParameters[] = {
    {"slices", 32, 4, 64, 4, "opacity planes over the light's caster depth range"},
    {"depth_bias", 1, 0, 16, 0, "slices a receiver looks up in front of itself, against self-shadowing"},
};

}  // namespace

const ShadowTechnique& osm_technique() {
  static const OpacityMapTechnique technique({"osm", "opacity shadow maps: optical depth at K planes", "OSM-", "slices", 4,
                                              "passes/shadows/techniques/osm/osm_build.comp", "osm build",
                                              "passes/shadows/techniques/osm/osm_fixed_build.comp", "osm fixed build", kOsmParameters});
  return technique;
}

}  // namespace avsm::passes
