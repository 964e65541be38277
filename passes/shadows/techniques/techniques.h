#pragma once
// The registry of shadow techniques (registry.h lists them; technique.h says what
// one is). Everything that offers, checks or describes techniques goes through here.
#include <span>
#include <string>
#include <string_view>

#include "passes/shadows/techniques/technique.h"

namespace avsm::passes {

// Every technique, in registry order.
std::span<const ShadowTechnique* const> shadow_techniques();
// Null when no technique has that name.
const ShadowTechnique* find_shadow_technique(std::string_view name);
// Throws std::invalid_argument listing the known names.
const ShadowTechnique& shadow_technique(std::string_view name);
// "avsm, uncompressed, ...".
std::string shadow_technique_names();
// The technique's code (GpuShadow::technique) by name.
uint32_t shadow_technique_code(std::string_view name);

// Checks a light's settings: a known technique, known parameters in range (a
// parameter may belong to another technique, so a light can switch), then the
// technique's own checks. Errors name `who`, the setting and what to use.
void check_shadow_settings(const scene::ShadowSettings& settings, const std::string& who);

// Help text for command lines: each technique and its parameters, one line each,
// indented by `indent` spaces.
std::string shadow_technique_help(int indent);

}  // namespace avsm::passes
