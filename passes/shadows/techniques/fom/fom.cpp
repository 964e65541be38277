// Fourier opacity maps (Jansen & Bavoil 2010): the optical depth along the light's
// caster depth range as K Fourier terms (fom_build.comp, K (a, b) pairs).
#include "passes/shadows/techniques/opacity_map_technique.h"

namespace avsm::passes {
namespace {

constexpr TechniqueParameter kFomParameters[] = {
    {"terms", 16, 2, 32, 2, "Fourier terms of the optical depth"},
    {"depth_bias", 1, 0, 16, 0, "slices (range / K) a receiver looks up in front of itself, against self-shadowing"},
};

}  // namespace

const ShadowTechnique& fom_technique() {
  static const OpacityMapTechnique technique({"fom", "Fourier opacity maps: optical depth as K Fourier terms", "FOM-",
                                              "terms", 8, "passes/shadows/techniques/fom/fom_build.comp", "fom build",
                                              "passes/shadows/techniques/fom/fom_fixed_build.comp", "fom fixed build",
                                              kFomParameters});
  return technique;
}

}  // namespace avsm::passes
