#include "passes/shadows/techniques/techniques.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace avsm::passes {

// Each technique's folder defines <name>_technique().
#define AVSM_SHADOW_TECHNIQUE(name) const ShadowTechnique& name##_technique();
#include "passes/shadows/techniques/registry.h"
#undef AVSM_SHADOW_TECHNIQUE

std::span<const ShadowTechnique* const> shadow_techniques() {
  static const std::vector<const ShadowTechnique*> list = {
#define AVSM_SHADOW_TECHNIQUE(name) &name##_technique(),
#include "passes/shadows/techniques/registry.h"
#undef AVSM_SHADOW_TECHNIQUE
  };
  return list;
}

uint32_t ShadowTechnique::code() const {
  const std::span<const ShadowTechnique* const> all = shadow_techniques();
  for (size_t i = 0; i < all.size(); ++i)
    if (all[i] == this) return uint32_t(i + 1);
  throw std::logic_error("shadow technique '" + std::string(name()) + "' is not in passes/shadows/techniques/registry.h");
}

const ShadowTechnique* find_shadow_technique(std::string_view name) {
  for (const ShadowTechnique* t : shadow_techniques())
    if (t->name() == name) return t;
  return nullptr;
}

std::string shadow_technique_names() {
  std::string names;
  for (const ShadowTechnique* t : shadow_techniques()) names += (names.empty() ? "" : ", ") + std::string(t->name());
  return names;
}

const ShadowTechnique& shadow_technique(std::string_view name) {
  if (const ShadowTechnique* t = find_shadow_technique(name)) return *t;
  throw std::invalid_argument("'" + std::string(name) + "' is not one of " + shadow_technique_names());
}

uint32_t shadow_technique_code(std::string_view name) { return shadow_technique(name).code(); }

namespace {

const TechniqueParameter* find_parameter(const ShadowTechnique& t, std::string_view name) {
  for (const TechniqueParameter& p : t.parameters())
    if (p.name == name) return &p;
  return nullptr;
}

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string accepted_values(const TechniqueParameter& p) {
  if (p.multiple_of > 0.0)
    return "a multiple of " + number_text(p.multiple_of) + " from " + number_text(p.min) + " to " + number_text(p.max);
  return "a value from " + number_text(p.min) + " to " + number_text(p.max);
}

void check_parameter(const ShadowTechnique& t, const TechniqueParameter& p, double value, const std::string& who) {
  const bool in_range = value >= p.min && value <= p.max;
  const bool multiple = p.multiple_of <= 0.0 || std::fmod(value, p.multiple_of) == 0.0;
  if (!in_range || !multiple)
    throw std::invalid_argument(who + ": " + std::string(t.name()) + " parameter " + std::string(p.name) + " = " +
                                number_text(value) + "; use " + accepted_values(p));
}

// Names every technique reads, once each in registry order, for the error on a
// parameter none of them knows.
std::string all_parameter_names() {
  std::vector<std::string_view> names;
  for (const ShadowTechnique* t : shadow_techniques())
    for (const TechniqueParameter& p : t->parameters())
      if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
  std::string text;
  for (std::string_view name : names) text += (text.empty() ? "" : ", ") + std::string(name);
  return text;
}

}  // namespace

void check_shadow_settings(const scene::ShadowSettings& settings, const std::string& who) {
  const ShadowTechnique* technique = find_shadow_technique(settings.technique);
  if (!technique)
    throw std::invalid_argument(who + ": technique '" + settings.technique + "' is not one of " +
                                shadow_technique_names());
  for (const auto& [name, value] : settings.parameters) {
    if (const TechniqueParameter* p = find_parameter(*technique, name)) {
      check_parameter(*technique, *p, value, who);
      continue;
    }
    bool known = false;
    for (const ShadowTechnique* other : shadow_techniques()) known |= find_parameter(*other, name) != nullptr;
    if (!known)
      throw std::invalid_argument(who + ": '" + name + "' is not a parameter of any technique (" +
                                  all_parameter_names() + ")");
  }
  if (settings.build == scene::ShadowBuild::fixed && !technique->builds_fixed()) {
    std::string fixed;
    for (const ShadowTechnique* t : shadow_techniques())
      if (t->builds_fixed()) fixed += (fixed.empty() ? "" : ", ") + std::string(t->name());
    throw std::invalid_argument(who + ": technique '" + settings.technique +
                                "' builds from capture lists only; set build to \"lists\" (--build lists) or use " +
                                fixed);
  }
  technique->check(settings, who);
}

std::string shadow_technique_help(int indent) {
  const std::string pad(size_t(indent), ' ');
  std::string help;
  for (const ShadowTechnique* t : shadow_techniques()) {
    help += pad + std::string(t->name()) + ": " + std::string(t->summary()) + "\n";
    for (const TechniqueParameter& p : t->parameters())
      help += pad + "  " + std::string(p.name) + " (default " + number_text(p.default_value) + ", " +
              accepted_values(p) + "): " + std::string(p.meaning) + "\n";
  }
  return help;
}

// ---------------------------------------------------------------- defaults

void ShadowTechnique::check(const scene::ShadowSettings&, const std::string&) const {}

uint64_t ShadowTechnique::map_bytes(const scene::ShadowSettings&, const TechniqueMapState&) const { return 0; }

void ShadowTechnique::fill(shared::GpuShadow&, const scene::ShadowSettings&, const LightView&) const {}

std::unique_ptr<TechniqueBuilder> ShadowTechnique::create_builder(gpu::Context&, const gpu::ShaderLibrary&) const {
  return nullptr;
}

rg::BufferHandle TechniqueBuilder::add_fixed_to_graph(const FixedTechniqueBuild& build) const {
  throw std::logic_error(build.prefix + ": technique '" + build.settings.technique + "' has no fixed-memory build");
}

bool ShadowTechnique::finish_frame(const uint32_t[3], TechniqueMapState&, LightShadowStats&) const { return false; }

double ShadowTechnique::parameter(const scene::ShadowSettings& settings, std::string_view name) const {
  const TechniqueParameter* p = find_parameter(*this, name);
  if (!p) throw std::logic_error(std::string(this->name()) + " reads an undeclared parameter '" + std::string(name) + "'");
  return settings.parameter(std::string(name), p->default_value);
}

}  // namespace avsm::passes
