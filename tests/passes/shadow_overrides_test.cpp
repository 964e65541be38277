// passes::apply_shadow_overrides(): overrides that only a dense map can honour make a
// paged light dense, unless they name the layout; the others keep it paged.
#include <gtest/gtest.h>

#include "passes/shadows/shadow_settings.h"

namespace avsm {
namespace {

scene::Light paged_light(scene::LightType type) {
  scene::Light light;
  light.type = type;
  light.shadow.layout = scene::ShadowLayout::paged;
  light.shadow.fit = scene::ShadowFit::scene;
  return light;
}

scene::ShadowLayout layout_after(const scene::ShadowOverrides& overrides,
                                 scene::LightType type = scene::LightType::directional) {
  scene::Light light = paged_light(type);
  passes::apply_shadow_overrides(overrides, light);
  return light.shadow.layout;
}

TEST(ShadowOverrides, DenseOnlySettingsMakeAPagedLightDense) {
  using scene::ShadowLayout;
  EXPECT_EQ(layout_after({.technique = "dsm"}), ShadowLayout::dense);
  EXPECT_EQ(layout_after({.resolution = 64}), ShadowLayout::dense);
  EXPECT_EQ(layout_after({.kernel = scene::ShadowKernel::gaussian}), ShadowLayout::dense);
  EXPECT_EQ(layout_after({.build = scene::ShadowBuild::fixed}), ShadowLayout::dense);
  EXPECT_EQ(layout_after({.fit = scene::ShadowFit::view}), ShadowLayout::dense);
  EXPECT_EQ(layout_after({.cascades = 3}), ShadowLayout::dense);
  EXPECT_EQ(layout_after({.clusters = 4}, scene::LightType::spot), ShadowLayout::dense);
}

// A paged sun covers the scene; the cascades asked for split the camera's view instead.
TEST(ShadowOverrides, CascadesMakeAPagedSunDenseAndFittedToTheView) {
  scene::Light sun = paged_light(scene::LightType::directional);
  passes::apply_shadow_overrides({.cascades = 4}, sun);
  EXPECT_EQ(sun.shadow.layout, scene::ShadowLayout::dense);
  EXPECT_EQ(sun.shadow.fit, scene::ShadowFit::view);
  EXPECT_NO_THROW(passes::check_light_settings(sun, 0));
}

TEST(ShadowOverrides, SettingsPagesHoldKeepThePagedLayout) {
  using scene::ShadowLayout;
  EXPECT_EQ(layout_after({.technique = "avsm", .nodes = 4}), ShadowLayout::paged);
  EXPECT_EQ(layout_after({.technique = "uncompressed"}), ShadowLayout::paged);
  EXPECT_EQ(layout_after({.kernel = scene::ShadowKernel::none, .build = scene::ShadowBuild::lists}), ShadowLayout::paged);
  EXPECT_EQ(layout_after({.fit = scene::ShadowFit::view}, scene::LightType::spot), ShadowLayout::paged);
  // Settings the light's type does not take are not applied (ShadowOverrides::apply(Light&)).
  EXPECT_EQ(layout_after({.cascades = 3}, scene::LightType::spot), ShadowLayout::paged);
  EXPECT_EQ(layout_after({.clusters = 4}, scene::LightType::point), ShadowLayout::paged);
  // An unknown technique is left for check_light_settings() to name.
  EXPECT_EQ(layout_after({.technique = "bogus"}), ShadowLayout::paged);
}

TEST(ShadowOverrides, ANamedLayoutWins) {
  scene::Light light = paged_light(scene::LightType::spot);
  passes::apply_shadow_overrides({.technique = "dsm", .layout = scene::ShadowLayout::paged}, light);
  EXPECT_EQ(light.shadow.layout, scene::ShadowLayout::paged);
  EXPECT_THROW(passes::check_paged_settings(light, "light 0"), std::invalid_argument);

  scene::Light dense = paged_light(scene::LightType::spot);
  dense.shadow.layout = scene::ShadowLayout::dense;
  passes::apply_shadow_overrides({.layout = scene::ShadowLayout::paged}, dense);
  EXPECT_EQ(dense.shadow.layout, scene::ShadowLayout::paged);
}

}  // namespace
}  // namespace avsm
