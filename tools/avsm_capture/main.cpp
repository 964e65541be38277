// avsm-capture: renders a scene headless and writes images and per-pass timings.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>

#include "capture/capture.h"
#include "passes/techniques/techniques.h"

namespace {

const char* kUsage =
    "usage: avsm-capture [options]\n"
    "  --scene FILE     scene JSON (default: the generated default scene)\n"
    "  --camera NAME    camera by name or index (default: the scene's first)\n"
    "  --out DIR        output folder (default out/capture)\n"
    "  --width N        image width (default 1280)\n"
    "  --height N       image height (default 720)\n"
    "  --frames K       frames to render; timings over all but the first (default 5)\n"
    "  --frames-in-flight N  frames recorded ahead of the GPU, 1 to 3 (default 2)\n"
    "  --device NAME    Vulkan device: index or part of its name (env AVSM_DEVICE)\n"
    "  --validation     enable Vulkan validation + synchronization validation\n"
    "  --quiet          no progress on stderr\n"
    "  --report         also write report.html: one self-contained page with the images,\n"
    "                   pass timings, memory figures and frame graph\n"
    "volume shading (default: the scene file's volume_shading):\n"
    "  --volume-shading fast|reference|hidden   fast: lighting cache, reduced-resolution march,\n"
    "                   per-vertex hair lighting; reference: full resolution, quarter-voxel\n"
    "                   steps, shadow lookups along every ray (default fast); hidden: the\n"
    "                   camera does not see the volumes (they still cast shadows)\n"
    "  --volume-resolution-divisor 1|2|4   fast march resolution: 1/N per axis (default 2)\n"
    "  --volume-step VOXELS   fast march step, 0.125 to 4 voxels (default 2)\n"
    "  --compare-volume-shading   also render every frame the reference way (interleaved)\n"
    "                   and once with the volumes hidden: volume_quality.json (smoke-pixel\n"
    "                   error of this shading against the reference, both paths' pass ms),\n"
    "                   volume_error.png (error x10), frame_reference.exr\n"
    "shadow overrides, for every light (default: the scene file's settings):\n"
    "  --technique T    one of the shadow techniques listed at the end"" (default avsm)\n"
    "  --nodes N        AVSM nodes per texel: 4, 8, 12 or 16\n"
    "  --sort on|off    sort each texel's segments before the resolve (lists build)\n"
    "  --build lists|fixed  how AVSM maps are built: per-texel fragment lists then a\n"
    "                   resolve, or straight from the casters in fixed memory\n"
    "  --filter F       point | bilinear | trilinear (trilinear builds the mip chain)\n"
    "  --kernel K       none | box | gaussian: soft surface shadows over curves at texel centres\n"
    "  --kernel-radius R  the kernel's radius in texels, 1 to 4 (box: 2R + 1 wide; gaussian: sigma R / 2)\n"
    "  --shadow-res R   transmittance map texels per side (of each map: cube face, cascade, cluster)\n"
    "  --cascades N     directional lights (only): maps split along the camera's view, 1 to 4\n"
    "  --clusters N     directional and spot lights (not point): casters grouped by their\n"
    "                   light-space bounds, at most N maps (up to 8) of the shadow resolution\n"
    "                   each; 1: off; 0: the scene's \"shadows\" clusters. Not with --cascades > 1\n"
    "  --shadow-param NAME=NUMBER   (repeatable) a technique parameter (listed at the end)\n"
    "  --interpolation linear|exponential   between AVSM nodes (default linear)\n"
    "  --probe FILE     JSON array [[x,y,z],...]: writes probes.json with each light's\n"
    "                   transmittance at every point\n"
    "shadow quality against the exact reference (keeps every light's capture lists):\n"
    "  --compare-to uncompressed   per light, |T - T_exact| at the surfaces and smoke the\n"
    "                   camera sees: quality.json and light<i>_error.png (error x4)\n"
    "  --plot-texel LIGHT:X,Y      (repeatable) LIGHT: index or name; X,Y: level-0 texel\n"
    "                   (y = 0 at the bottom of light<i>_transmittance.png): writes\n"
    "                   curve_<light index>_<x>_<y>.svg, the technique's curve over the exact one\n"
    "  --list-techniques   the shadow techniques' names, one per line\n"
    "  --help           this text\n";

// The options, then every registered shadow technique with its parameters.
std::string usage() {
  return std::string(kUsage) + "shadow techniques (--technique) and their parameters (--shadow-param):\n" +
         avsm::passes::shadow_technique_help(2);
}

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "avsm-capture: %s\n%s", message.c_str(), usage().c_str());
  std::exit(2);
}

// A whole number in [lo, hi], or a usage error naming the flag and the range.
int parse_in_range(const std::string& flag, const std::string& value, int lo, int hi) {
  try {
    size_t used = 0;
    const long long n = std::stoll(value, &used);
    if (used == value.size() && n >= lo && n <= hi) return int(n);
  } catch (const std::exception&) {
  }
  usage_error(flag + " expects a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got '" +
              value + "'");
}

uint32_t parse_count(const std::string& flag, const std::string& value) {
  try {
    size_t used = 0;
    long long n = std::stoll(value, &used);
    if (used != value.size() || n < 1 || n > 1000000) throw std::invalid_argument("range");
    return uint32_t(n);
  } catch (const std::exception&) {
    usage_error(flag + " expects a positive whole number, got '" + value + "'");
  }
}

bool parse_on_off(const std::string& flag, const std::string& value) {
  if (value == "on") return true;
  if (value == "off") return false;
  usage_error(flag + " expects on or off, got '" + value + "'");
}

}  // namespace

int main(int argc, char** argv) {
  avsm::capture::CaptureOptions options;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf("%s", usage().c_str());
      return 0;
    } else if (arg == "--list-techniques") {  // for scripts: one registered technique name per line
      for (const avsm::passes::ShadowTechnique* t : avsm::passes::shadow_techniques())
        std::printf("%.*s\n", int(t->name().size()), t->name().data());
      return 0;
    } else if (arg == "--scene") {
      options.scene = value();
    } else if (arg == "--camera") {
      options.camera = value();
    } else if (arg == "--out") {
      options.out_dir = value();
    } else if (arg == "--width") {
      options.width = parse_count(arg, value());
    } else if (arg == "--height") {
      options.height = parse_count(arg, value());
    } else if (arg == "--frames") {
      options.frames = parse_count(arg, value());
    } else if (arg == "--frames-in-flight") {
      options.frames_in_flight = parse_count(arg, value());
    } else if (arg == "--device") {
      options.device = value();
    } else if (arg == "--validation") {
      options.validation = true;
    } else if (arg == "--quiet") {
      options.progress = false;
    } else if (arg == "--report") {
      options.report = true;
    } else if (arg == "--volume-shading") {
      const std::string name = value();
      options.volume_shading.mode = avsm::scene::volume_shading_mode_from_string(name);
      if (!options.volume_shading.mode) usage_error("--volume-shading expects fast, reference or hidden, got '" + name + "'");
    } else if (arg == "--volume-resolution-divisor") {
      const uint32_t n = parse_count(arg, value());
      if (n != 1 && n != 2 && n != 4) usage_error("--volume-resolution-divisor expects 1, 2 or 4");
      options.volume_shading.resolution_divisor = int(n);
    } else if (arg == "--volume-step") {
      const std::string text = value();
      float voxels = 0.0f;
      try {
        size_t used = 0;
        voxels = std::stof(text, &used);
        if (used != text.size()) throw std::invalid_argument("form");
      } catch (const std::exception&) {
        usage_error("--volume-step expects a number of voxels, got '" + text + "'");
      }
      if (!(voxels >= 0.125f && voxels <= 4.0f)) usage_error("--volume-step expects 0.125 to 4 voxels");
      options.volume_shading.step_voxels = voxels;
    } else if (arg == "--compare-volume-shading") {
      options.compare_volume_shading = true;
    } else if (arg == "--technique") {
      const std::string name = value();
      if (!avsm::passes::find_shadow_technique(name))
        usage_error("--technique expects one of " + avsm::passes::shadow_technique_names() + ", got '" + name + "'");
      options.shadow.technique = name;
    } else if (arg == "--nodes") {
      const uint32_t n = parse_count(arg, value());
      if (n != 4 && n != 8 && n != 12 && n != 16) usage_error("--nodes expects 4, 8, 12 or 16");
      options.shadow.nodes = int(n);
    } else if (arg == "--sort") {
      options.shadow.sort = parse_on_off(arg, value());
    } else if (arg == "--build") {
      const std::string name = value();
      options.shadow.build = avsm::scene::shadow_build_from_string(name);
      if (!options.shadow.build) usage_error("--build expects lists or fixed, got '" + name + "'");
    } else if (arg == "--filter") {
      const std::string name = value();
      options.shadow.filter = avsm::scene::shadow_filter_from_string(name);
      if (!options.shadow.filter) usage_error("--filter expects point, bilinear or trilinear, got '" + name + "'");
    } else if (arg == "--kernel") {
      const std::string name = value();
      options.shadow.kernel = avsm::scene::shadow_kernel_from_string(name);
      if (!options.shadow.kernel) usage_error("--kernel expects none, box or gaussian, got '" + name + "'");
    } else if (arg == "--kernel-radius") {
      const uint32_t r = parse_count(arg, value());
      if (r < 1 || r > 4) usage_error("--kernel-radius expects 1 to 4 texels");
      options.shadow.kernel_radius = int(r);
    } else if (arg == "--shadow-res") {
      const uint32_t r = parse_count(arg, value());
      if (r > 16384) usage_error("--shadow-res expects at most 16384");
      options.shadow.resolution = int(r);
    } else if (arg == "--cascades") {
      options.shadow.cascades = parse_in_range(arg, value(), 1, 4);
    } else if (arg == "--clusters") {
      options.shadow.clusters = parse_in_range(arg, value(), 0, 8);
    } else if (arg == "--interpolation") {
      const std::string name = value();
      if (name != "linear" && name != "exponential")
        usage_error("--interpolation expects linear or exponential, got '" + name + "'");
      options.exponential_interpolation = name == "exponential";
    } else if (arg == "--probe") {
      options.probe_file = value();
    } else if (arg == "--shadow-param") {
      const std::string text = value();
      const size_t equals = text.find('=');
      double number = 0;
      try {
        size_t used = 0;
        if (equals == std::string::npos || equals == 0) throw std::invalid_argument("form");
        number = std::stod(text.substr(equals + 1), &used);
        if (used != text.size() - equals - 1 || !std::isfinite(number)) throw std::invalid_argument("number");
      } catch (const std::exception&) {
        usage_error("--shadow-param expects NAME=NUMBER (e.g. error=0.01, slices=32, terms=16), got '" + text + "'");
      }
      options.shadow.parameters[text.substr(0, equals)] = number;
    } else if (arg == "--compare-to") {
      const std::string name = value();
      if (name != "uncompressed")
        usage_error("--compare-to expects uncompressed (the exact reference), got '" + name + "'");
      options.compare_to_uncompressed = true;
    } else if (arg == "--plot-texel") {
      const std::string spec = value();
      std::optional<avsm::capture::TexelPlot> plot = avsm::capture::parse_texel_plot(spec);
      if (!plot)
        usage_error("--plot-texel expects LIGHT:X,Y (light index or name, level-0 texel), got '" + spec + "'");
      options.plot_texels.push_back(*plot);
    } else {
      usage_error("unknown option '" + arg + "'");
    }
  }
  // A light is either cascaded or clustered (both split it into maps of their own kind).
  if (options.shadow.cascades.value_or(1) > 1 && options.shadow.clusters.value_or(0) > 1)
    usage_error("--cascades and --clusters exclude each other: a light's maps are either cascades or clusters");
  try {
    avsm::capture::CaptureOutputs out = avsm::capture::run_capture(options);
    std::printf("image:   %s\nhdr:     %s\ntimings: %s\n", out.png.c_str(), out.exr.c_str(), out.timings.c_str());
    if (!out.quality.empty()) std::printf("quality: %s\n", out.quality.c_str());
    if (!out.volume_quality.empty()) std::printf("volume quality: %s\n", out.volume_quality.c_str());
    for (const auto& curve : out.curves) std::printf("curve:   %s\n", curve.c_str());
    if (options.report) std::printf("report:  %s\n", (options.out_dir / "report.html").c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avsm-capture: error: %s\n", e.what());
    return 1;
  }
}
