// The shadow technique registry (passes/shadows/techniques/): what every technique declares,
// the checks made from it, and the GLSL dispatch the build generates from the same list.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "gpu/shader_compiler.h"
#include "passes/shadows/techniques/techniques.h"

namespace avsm {
namespace technique_registry_test {  // one per file: test targets are unity builds
namespace {

using ::testing::HasSubstr;

std::string check_error(const scene::ShadowSettings& settings) {
  try {
    passes::check_shadow_settings(settings, "light 0 'sun'");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

scene::ShadowSettings settings_of(const std::string& technique, std::map<std::string, double> parameters = {}) {
  scene::ShadowSettings s;
  s.technique = technique;
  s.parameters = std::move(parameters);
  return s;
}

TEST(TechniqueRegistry, ListsEveryTechniqueOnceWithConsecutiveCodes) {
  std::set<std::string> names;
  uint32_t code = 1;
  for (const passes::ShadowTechnique* t : passes::shadow_techniques()) {
    EXPECT_TRUE(names.insert(std::string(t->name())).second) << t->name();
    EXPECT_EQ(t->code(), code++) << t->name();
    EXPECT_FALSE(t->summary().empty()) << t->name();
    EXPECT_EQ(&passes::shadow_technique(t->name()), t);
  }
  for (const char* expected : {"avsm", "uncompressed", "osm", "fom", "dsm", "constant"})
    EXPECT_TRUE(names.count(expected)) << expected;
  EXPECT_EQ(passes::find_shadow_technique("vsm"), nullptr);
}

TEST(TechniqueRegistry, UnknownTechniquesAndParametersAreClearErrors) {
  EXPECT_EQ(check_error(settings_of("avsm")), "");
  EXPECT_THAT(check_error(settings_of("vsm")),
              HasSubstr("light 0 'sun': technique 'vsm' is not one of " + passes::shadow_technique_names()));
  EXPECT_THAT(passes::shadow_technique_names(), HasSubstr("avsm, uncompressed, osm, fom, dsm"));
  EXPECT_THAT(check_error(settings_of("osm", {{"slics", 32}})),
              HasSubstr("'slics' is not a parameter of any technique (page_segments, slices, depth_bias, terms, error, transmittance"));
  // Another technique's parameter is kept, so a light can switch techniques.
  EXPECT_EQ(check_error(settings_of("avsm", {{"slices", 32}})), "");
}

TEST(TechniqueRegistry, ParametersAreCheckedAgainstTheirDeclaredRanges) {
  EXPECT_EQ(check_error(settings_of("osm", {{"slices", 64}})), "");
  EXPECT_THAT(check_error(settings_of("osm", {{"slices", 30}})),
              HasSubstr("light 0 'sun': osm parameter slices = 30; use a multiple of 4 from 4 to 64"));
  EXPECT_THAT(check_error(settings_of("fom", {{"terms", 33}})), HasSubstr("use a multiple of 2 from 2 to 32"));
  EXPECT_THAT(check_error(settings_of("dsm", {{"error", 0}})), HasSubstr("dsm parameter error = 0.000000; use a value in (0, 1)"));
  EXPECT_THAT(check_error(settings_of("constant", {{"transmittance", 1.5}})), HasSubstr("use a value from 0 to 1"));
}

TEST(TechniqueRegistry, LabelsUseTheDeclaredDefaults) {
  EXPECT_EQ(passes::shadow_technique("avsm").label(settings_of("avsm")), "AVSM-8");
  EXPECT_EQ(passes::shadow_technique("osm").label(settings_of("osm")), "OSM-32");
  EXPECT_EQ(passes::shadow_technique("fom").label(settings_of("fom", {{"terms", 8}})), "FOM-8");
  EXPECT_EQ(passes::shadow_technique("dsm").label(settings_of("dsm")), "DSM (error 0.01)");
  EXPECT_EQ(passes::shadow_technique("uncompressed").label(settings_of("uncompressed")), "uncompressed");
  EXPECT_EQ(passes::shadow_technique("constant").label(settings_of("constant")), "constant 0.5");
}

TEST(TechniqueRegistry, HelpListsEveryTechniqueAndParameter) {
  const std::string help = passes::shadow_technique_help(2);
  for (const passes::ShadowTechnique* t : passes::shadow_techniques()) {
    EXPECT_THAT(help, HasSubstr("  " + std::string(t->name()) + ": ")) << help;
    for (const passes::TechniqueParameter& p : t->parameters()) EXPECT_THAT(help, HasSubstr(std::string(p.name))) << help;
  }
  EXPECT_THAT(help, HasSubstr("slices (default 32, a multiple of 4 from 4 to 64)"));
}

// The build turns registry.h into the GLSL lookup dispatch: one branch per technique
// with its registry code, so C++ and shaders agree on the codes.
TEST(TechniqueRegistry, TheGeneratedGlslDispatchFollowsTheRegistry) {
  const auto file = gpu::ShaderLibrary::default_paths().spirv_root / "glsl" / "techniques_lookup.glsl";
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  std::stringstream text;
  text << in.rdbuf();
  for (const passes::ShadowTechnique* t : passes::shadow_techniques()) {
    const std::string name(t->name());
    EXPECT_THAT(text.str(), HasSubstr("#include \"techniques/" + name + "/" + name + ".glsl\""));
    EXPECT_THAT(text.str(), HasSubstr("if (s.technique == " + std::to_string(t->code()) + "u) return " + name +
                                      "_lookup(s, level, texel, d);"));
  }
}

}  // namespace
}  // namespace technique_registry_test
}  // namespace avsm
