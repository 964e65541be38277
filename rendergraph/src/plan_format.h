#pragma once
// Small formatting helpers shared by the text, JSON and DOT dumps of a plan.
#include <rendergraph/plan.h>
#include <rendergraph/vk_names.h>

#include <string>

#include "text.h"

namespace rg::detail {

inline std::string usage_names(UsageSet usages) {
  std::string text;
  usages.for_each([&](Usage usage) {
    if (!text.empty()) text += '+';
    text += to_string(usage);
  });
  return text.empty() ? "none" : text;
}

// "1920x1080 R16G16B16A16_SFLOAT", "256x256x64 mips 9 layers 6 ...", "4096 bytes".
inline std::string desc_text(const PlannedResource& r) {
  if (r.kind == ResourceKind::Buffer) return cat(std::to_string(r.buffer.size), " bytes");
  const TextureDesc& d = r.texture;
  std::string text = cat(std::to_string(d.width), "x", std::to_string(d.height));
  if (d.depth > 1) text += cat("x", std::to_string(d.depth));
  text += cat(" ", format_name(d.format));
  if (d.mip_levels > 1) text += cat(" mips ", std::to_string(d.mip_levels));
  if (d.array_layers > 1) text += cat(" layers ", std::to_string(d.array_layers));
  return text;
}

// "COMPUTE_SHADER/SHADER_STORAGE_WRITE" (+ "/GENERAL" for textures).
inline std::string state_text(const ImportState& state, ResourceKind kind) {
  std::string text = cat(stage_names(state.stages), "/", access_names(state.access));
  if (kind == ResourceKind::Texture) text += cat("/", layout_name(state.layout));
  return text;
}

}  // namespace rg::detail
