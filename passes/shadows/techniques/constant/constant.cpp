// A debug technique: every point a light reaches gets the same transmittance, with no
// capture read and no map. It shows a light's reach and the lookup plumbing on their
// own (a shadow bug that stays with `constant` is not the technique's), and is the
// smallest example of a technique: this file, constant.glsl and its registry line.
#include "passes/shadows/techniques/technique.h"

namespace avsm::passes {
namespace {

constexpr TechniqueParameter kParameters[] = {
    {"transmittance", 0.5, 0, 1, 0, "what every lookup returns"},
};

class Constant final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "constant"; }
  std::string_view summary() const override { return "debug: one transmittance everywhere the light reaches"; }
  std::span<const TechniqueParameter> parameters() const override { return kParameters; }
  std::string label(const scene::ShadowSettings& s) const override {
    char text[48];
    std::snprintf(text, sizeof(text), "constant %g", parameter(s, "transmittance"));
    return text;
  }
  bool has_map() const override { return false; }
  void fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView&) const override {
    record.technique_data.x = float(parameter(s, "transmittance"));
  }
};

}  // namespace

const ShadowTechnique& constant_technique() {
  static const Constant technique;
  return technique;
}

}  // namespace avsm::passes
