// avsm-capture's command line (capture/capture_args.h): the flags written for any
// options parse back to the same options, and bad flags are usage errors naming them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "capture/capture_args.h"

namespace avsm::capture {
namespace capture_args_test {  // one per file: test targets are unity builds
namespace {

std::string usage_error_of(const std::vector<std::string>& args) {
  try {
    parse_capture_arguments(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(no error)";
}

CaptureOptions every_option_set() {
  CaptureOptions o;
  o.scene = "/scenes/x.scene.json";
  o.camera = "side";
  o.out_dir = "/tmp/out";
  o.width = 96;
  o.height = 54;
  o.frames = 2;
  o.frames_in_flight = 1;
  o.orbit_degrees = -2.5f;
  o.light_orbit_degrees = 1.25f;
  o.time = 0.75f;
  o.validation = true;
  o.device = "llvmpipe";
  o.progress = false;
  o.report = true;
  o.volume_shading.mode = scene::VolumeShading::Mode::reference;
  o.volume_shading.resolution_divisor = 4;
  o.volume_shading.step_voxels = 0.3f;  // not exact in binary: written as the shortest text that reads back
  o.compare_volume_shading = true;
  o.path_trace_volumes = 16;
  o.volume_octaves = 2;
  o.volume_sky_light = 0.3f;
  o.fog = true;
  o.compare_fog = true;
  o.shadow.technique = "osm";
  o.shadow.nodes = 12;
  o.shadow.resolution = 64;
  o.shadow.filter = scene::ShadowFilter::trilinear;
  o.shadow.kernel = scene::ShadowKernel::gaussian;
  o.shadow.kernel_radius = 3;
  o.shadow.sort = false;
  o.shadow.build = scene::ShadowBuild::fixed;
  o.shadow.fit = scene::ShadowFit::scene;
  o.shadow.cascades = 3;
  o.shadow.clusters = 1;
  o.shadow.page_builds_per_frame = 12;
  o.shadow.parameters = {{"slices", 32}, {"depth_bias", 0.1}};
  o.exponential_interpolation = true;
  o.probe_file = "/probes.json";
  o.compare_to_uncompressed = true;
  o.plot_texels = {*parse_texel_plot("sun:3,4"), *parse_texel_plot("1:0,0")};
  o.dump_passes = "/tmp/passes.json";
  return o;
}

TEST(CaptureArgs, EveryOptionRoundTrips) {
  const CaptureOptions options = every_option_set();
  const CaptureCommand parsed = parse_capture_arguments(capture_arguments(options));
  EXPECT_EQ(parsed.action, CaptureAction::capture);
  EXPECT_TRUE(parsed.options == options);
  EXPECT_NO_THROW(validate_capture_options(options));
}

TEST(CaptureArgs, DefaultsNeedNoFlags) {
  EXPECT_TRUE(capture_arguments(CaptureOptions{}).empty());
  EXPECT_TRUE(parse_capture_arguments({}).options == CaptureOptions{});
}

TEST(CaptureArgs, EachFlagAlone) {
  CaptureOptions options;
  options.shadow.sort = true;
  EXPECT_EQ(capture_arguments(options), (std::vector<std::string>{"--sort", "on"}));
  options = {};
  options.shadow.parameters["error"] = 0.01;
  EXPECT_EQ(capture_arguments(options), (std::vector<std::string>{"--shadow-param", "error=0.01"}));
}

TEST(CaptureArgs, HelpAndListStopTheParse) {
  EXPECT_EQ(parse_capture_arguments({"--width", "9", "--help", "--bogus"}).action, CaptureAction::help);
  EXPECT_EQ(parse_capture_arguments({"--list-techniques"}).action, CaptureAction::list_techniques);
  EXPECT_NE(capture_usage().find("--shadow-param NAME=NUMBER"), std::string::npos);
}

// A shot and its rate; --frames and the orbits do not apply to one.
TEST(CaptureArgs, AShotRoundTrips) {
  CaptureOptions o;
  o.frame_range = FrameRange{2, 9, 30.0f};
  o.fps = 30.0f;
  const CaptureOptions parsed = parse_capture_arguments(capture_arguments(o)).options;
  EXPECT_TRUE(parsed == o);
  const CaptureOptions one = parse_capture_arguments({"--frame-range", "7"}).options;
  ASSERT_TRUE(one.frame_range.has_value());
  EXPECT_EQ(one.frame_range->first, 7);
  EXPECT_EQ(one.frame_range->last, 7);
  EXPECT_FLOAT_EQ(one.frame_range->fps, 24.0f);
}

TEST(CaptureArgs, BadFlagsNameThemselves) {
  EXPECT_EQ(usage_error_of({"--frame-range", "5:2"}), "--frame-range expects A:B with 0 <= A <= B, got '5:2'");
  EXPECT_EQ(usage_error_of({"--fps", "0"}), "--fps expects a frame rate in (0, 1000], got '0'");
  EXPECT_EQ(usage_error_of({"--fps", "30"}), "--fps needs --frame-range (the shot it sets the rate of)");
  EXPECT_EQ(usage_error_of({"--time", "1", "--frame-range", "0:4"}),
            "--time and --frame-range exclude each other: a shot's frames set their own times");
  EXPECT_EQ(usage_error_of({"--time", "soon"}), "--time expects a number of seconds, got 'soon'");
  EXPECT_EQ(usage_error_of({"--bogus"}), "unknown option '--bogus'");
  EXPECT_EQ(usage_error_of({"--width"}), "--width needs a value");
  EXPECT_EQ(usage_error_of({"--nodes", "7"}), "--nodes expects 4, 8, 12 or 16");
  EXPECT_EQ(usage_error_of({"--fit", "box"}), "--fit expects view or scene, got 'box'");
  EXPECT_EQ(usage_error_of({"--volume-step", "1x"}), "--volume-step expects a number of voxels, got '1x'");
  EXPECT_EQ(usage_error_of({"--orbit", "120"}), "--orbit expects -90 to 90 degrees per frame, got '120'");
  EXPECT_EQ(usage_error_of({"--light-orbit", "x"}), "--light-orbit expects -90 to 90 degrees per frame, got 'x'");
  EXPECT_EQ(usage_error_of({"--volume-octaves", "9"}), "--volume-octaves expects 1 (single scattering) to 8");
  EXPECT_EQ(usage_error_of({"--sky-light", "-1"}), "--sky-light expects 0 to 4, got '-1'");
  EXPECT_EQ(usage_error_of({"--fog", "yes"}), "--fog expects on or off, got 'yes'");
  EXPECT_EQ(usage_error_of({"--fog", "off", "--compare-fog"}), "--compare-fog needs the fog on (drop --fog off)");
  EXPECT_EQ(usage_error_of({"--path-trace-volumes", "8"}),
            "--path-trace-volumes needs --compare-volume-shading (it compares with the frames that renders)");
  EXPECT_EQ(usage_error_of({"--cascades", "2", "--clusters", "3"}),
            "--cascades and --clusters exclude each other: a light's maps are either cascades or clusters");
  CaptureOptions options;
  options.shadow.nodes = 7;
  EXPECT_THROW(validate_capture_options(options), UsageError);
}

}  // namespace
}  // namespace capture_args_test
}  // namespace avsm::capture
