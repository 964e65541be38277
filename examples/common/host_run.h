#pragma once
// What the host examples (examples/host_embed, host_raw) do alike around their frames:
// the command line, the light, the shading pass's push constants, the frame's figures,
// and the end of a run (the picture written and checked, validation messages counted).
//
//   <host> [--out DIR] [--size PIXELS] [--validation] [--check] [--no-shadows] [--fixed-memory-build]
//          [--point-light]
// --validation (or AVSM_VALIDATION=1) enables VK_LAYER_KHRONOS_validation with
// synchronization validation. --no-shadows binds unshadowed inputs instead of the maps:
// the checks must then fail (the tests use it to show that they can).
#include <avsm/shadows.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "io/image_io.h"

#include "ground_scene.h"
#include "ground_shading.h"
#include "host_device.h"

namespace host {

struct Options {
  std::filesystem::path out = ".";
  uint32_t size = 128;
  bool validation = false, check = false, shadows = true;
  bool fixed_memory_build = false;  // build the map straight from the casters (avsm::Light)
  bool point_light = false;         // a point light (a cube of six maps) instead of the sun
  bool paged = false;               // a paged map: pages built as the shading asks for them
};

inline Options parse_options(int argc, char** argv) {
  Options options;
  const char* env = std::getenv("AVSM_VALIDATION");
  options.validation = env && std::strcmp(env, "0") != 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) options.out = argv[++i];
    else if (arg == "--size" && i + 1 < argc) options.size = uint32_t(std::stoul(argv[++i]));
    else if (arg == "--validation") options.validation = true;
    else if (arg == "--check") options.check = true;
    else if (arg == "--no-shadows") options.shadows = false;
    else if (arg == "--fixed-memory-build") options.fixed_memory_build = true;
    else if (arg == "--point-light") options.point_light = true;
    else if (arg == "--paged") options.paged = true;
    else throw std::invalid_argument("unknown option '" + arg +
                                     "' (--out DIR --size N --validation --check --no-shadows --fixed-memory-build "
                                     "--point-light --paged)");
  }
  g_point_light = options.point_light;
  return options;
}

// The one light: the sun along kLightTravel, or --point-light's.
inline avsm::Light make_light(const Options& options) {
  avsm::Light light;
  light.name = "sun";
  light.direction = kLightTravel;
  if (options.point_light) {
    light.name = "point";
    light.type = avsm::LightType::point;
    light.position = kPointLight;
    light.range = 30.0f;
  }
  light.nodes = 8;
  light.resolution = 256;
  light.fixed_memory_build = options.fixed_memory_build;
  if (options.paged) {  // a 4096^2 virtual map in 64^2 pages, of which the shading asks for a few
    light.paged = true;
    light.virtual_resolution = 4096;
    light.page_size = 64;
    light.page_pool_mib = 8.0f;
    // Every page asked for in the next frame: the example checks its second frame's shadows
    // against the geometry (an interactive host keeps the default budget, so that a frame
    // whose light moved stays within its cost).
    light.page_builds_per_frame = 0;
  }
  return light;
}

// The camera the shadows are built for: above the ground, looking down.
inline avsm::Camera make_camera(const Options& options) {
  return avsm::Camera{glm::vec3(0.0f, 10.0f, 0.0f), 0.8f, options.size};
}

inline void print_setup(avsm::gpu::Context& context, const avsm::Shadows& shadows) {
  std::printf("device: %s; shaders: %s\n", context.info().name.c_str(),
              shadows.shader_location().glsl_root.string().c_str());
}

inline avsm::shared::GroundPush ground_push() {
  return {{-kGroundHalf, -kGroundHalf, 2 * kGroundHalf, 2 * kGroundHalf},
          g_point_light ? glm::vec4(kPointLight, 1.0f) : glm::vec4(-kLightTravel, 0.0f)};
}

inline void print_stats(int frame, const std::vector<avsm::LightStats>& stats) {
  for (const avsm::LightStats& s : stats)
    std::printf("frame %d light '%s': %u map(s) of %u nodes, %ux%u, %llu segments captured (capacity %llu)%s, "
                "%llu bytes of fixed build\n", frame, s.name.c_str(), s.maps, s.nodes, s.resolution, s.resolution,
                (unsigned long long)s.segments_captured, (unsigned long long)s.segment_capacity,
                s.overflowed ? ", overflowed" : "", (unsigned long long)s.fixed_build_bytes);
  for (const avsm::LightStats& s : stats)
    if (s.pages)
      std::printf("frame %d light '%s': pages asked for %u, resident %u of %u, built %u, pending %u\n", frame,
                  s.name.c_str(), s.pages->requested, s.pages->resident, s.pages->slots, s.pages->built,
                  s.pages->pending);
}

// Writes ground.png, checks the picture (--check) and counts the engine's validation
// messages: the number of failures.
inline int report_picture(const avsm::gpu::ImageRGBA32F& image, const Options& options, avsm::gpu::Context& context) {
  int failures = 0;
  std::filesystem::create_directories(options.out);
  avsm::io::write_png_srgb(options.out / "ground.png", opaque(image));
  std::printf("wrote %s\n", (options.out / "ground.png").string().c_str());
  if (options.check) failures += check_against_geometry(image);
  if (context.validation_log().count() > 0) {
    std::fprintf(stderr, "%s\n", avsm::gpu::describe(context.validation_log().take()).c_str());
    ++failures;
  }
  return failures;
}

// After the engine let go of the device: the host's own validation messages.
inline int report_validation(const HostDevice& host, const Options& options) {
  std::printf("validation: %s\n", options.validation ? "on (with synchronization validation)" : "off");
  if (host.validation_messages() == 0) return 0;
  std::fprintf(stderr, "%d validation message(s)\n", host.validation_messages());
  return 1;
}

// main(): runs `run` (which returns its failures) and says how it went.
template <class Run>
int host_main(const char* name, int argc, char** argv, const Run& run) {
  try {
    const int failures = run(parse_options(argc, argv));
    if (failures == 0) std::printf("%s: all checks passed\n", name);
    else std::printf("%s: %d check(s) failed\n", name, failures);
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 2;
  }
}

}  // namespace host
