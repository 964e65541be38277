// The exact reference: no map; the camera passes walk the light's capture lists and
// multiply every segment's transmittance (the ground truth the others are measured by).
#include "passes/shadows/techniques/technique.h"

namespace avsm::passes {
namespace {

// Paged (shadow.layout "paged"), each page keeps its capture lists in a slot of the
// light's pool that holds this many segments per texel (passes/shadows/shadow_settings.h).
constexpr TechniqueParameter kParameters[] = {
    {"page_segments", 32, 1, 1024, 1, "paged: capture segments a page's slot holds per texel"},
};

class Uncompressed final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "uncompressed"; }
  std::string_view summary() const override { return "the exact reference: every captured segment, read at lookup"; }
  std::string label(const scene::ShadowSettings&) const override { return "uncompressed"; }
  std::span<const TechniqueParameter> parameters() const override { return kParameters; }
  bool has_map() const override { return false; }
  bool reads_capture_lists() const override { return true; }
  void fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView&) const override {
    record.node_count = uint32_t(s.nodes);
  }
};

}  // namespace

const ShadowTechnique& uncompressed_technique() {
  static const Uncompressed technique;
  return technique;
}

}  // namespace avsm::passes
