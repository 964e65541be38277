#include "passes/shadows/shadow_settings.h"

#include <stdexcept>

#include "passes/shadows/techniques/techniques.h"
#include "shared/shadow.h"

namespace avsm::passes {

std::string light_display_name(const scene::Light& light, size_t index) {
  return "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
}

void check_light_settings(const scene::Light& light, size_t index) {
  const std::string who = light_display_name(light, index);
  const scene::ShadowSettings& s = light.shadow;
  if (s.cascades < 1 || s.cascades > 4)
    throw std::invalid_argument(who + ": " + std::to_string(s.cascades) + " cascades; use 1 to 4");
  if (s.cascades > 1 && light.type != scene::LightType::directional)
    throw std::invalid_argument(who + ": cascades split a directional light's view; set shadow.cascades to 1 for a " +
                                std::string(scene::to_string(light.type)) + " light");
  if (s.cascades > 1 && s.fit != scene::ShadowFit::view)
    throw std::invalid_argument(who + ": cascades follow the camera; set shadow.fit to \"view\"");
  if (s.clusters < 0 || s.clusters > int(shared::kMaxViewsPerLight))
    throw std::invalid_argument(who + ": " + std::to_string(s.clusters) + " clusters; use 0 (off) to " +
                                std::to_string(shared::kMaxViewsPerLight));
  if (s.clusters > 1 && (light.type == scene::LightType::point || s.cascades > 1))
    throw std::invalid_argument(who + ": clustered maps are for directional and spot lights without cascades; "
                                "set shadow.clusters to 0");
  if (s.nodes < 4 || s.nodes > 16 || s.nodes % 4 != 0)
    throw std::invalid_argument(who + ": " + std::to_string(s.nodes) + " AVSM nodes; use 4, 8, 12 or 16");
  if (s.kernel_radius < 1 || s.kernel_radius > int(shared::kMaxKernelRadius))
    throw std::invalid_argument(who + ": shadow kernel radius " + std::to_string(s.kernel_radius) + " texels; use 1 to " +
                                std::to_string(shared::kMaxKernelRadius));
  if (s.resolution < 1 || s.resolution > 16384)
    throw std::invalid_argument(who + ": shadow resolution " + std::to_string(s.resolution) + " is outside 1..16384");
  check_shadow_settings(s, who);
}

}  // namespace avsm::passes
