#include "capture/capture_args.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <optional>

#include "passes/shadows/techniques/techniques.h"

namespace avsm::capture {
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
    "  --time SECONDS   the instant to render: the scene's animation posed there (default:\n"
    "                   everything where the file places it)\n"
    "  --frame-range A:B  render a shot: frames A to B of the scene's animation, each once,\n"
    "                   as frames/frame_NNNN.png with shot.json (per-frame times, the first\n"
    "                   kept apart); the last frame's outputs as for one instant\n"
    "  --fps F          the shot's frame rate (default 24): frame N is the instant N / F\n"
    "  --orbit DEGREES  turn the camera about its target by this much each frame (default 0)\n"
    "  --light-orbit DEGREES  turn every light about the vertical axis through the scene's\n"
    "                   centre by this much each frame (default 0): a moving light\n"
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
    "  --path-trace-volumes PATHS   with --compare-volume-shading: also path trace the\n"
    "                   volumes on the CPU (every order of scattering) with PATHS paths a\n"
    "                   pixel, 1 to 4096: frame_path_traced.exr, and the smoke's mean\n"
    "                   luminance in each frame in volume_quality.json's \"path_traced\"\n"
    "  --volume-octaves N   every volume's multiple-scattering octaves, 1 (single\n"
    "                   scattering) to 8 (default: the scene file's, 4)\n"
    "  --sky-light S    every volume's share of the sky's light, 0 (none) to 4 (default:\n"
    "                   the scene file's, 1)\n"
    "  --fog on|off     show the scene's fog or not (default: on when the scene has one)\n"
    "  --area-shadows filtered|exact\n"
    "                   area lights' soft shadows on surfaces from a few of their virtual\n"
    "                   lights per pixel, filtered over neighbouring pixels, or from all of\n"
    "                   them at every pixel (default: filtered; exact with --volume-shading\n"
    "                   reference)\n"
    "  --compare-fog    also render the last frame with the fog marched per pixel (every\n"
    "                   light's map looked up per step) and without fog: fog_quality.json\n"
    "                   (relative L1 of the fog's effect, bound 5%), frame_fog_reference.exr\n"
    "shadow overrides, for every light (default: the scene file's settings):\n"
    "  --technique T    one of the shadow techniques listed at the end (default avsm)\n"
    "  --nodes N        AVSM nodes per texel: 4, 8, 12 or 16\n"
    "  --sort on|off    sort each texel's segments before the resolve (lists build)\n"
    "  --build lists|fixed  how AVSM maps are built: per-texel fragment lists then a\n"
    "                   resolve, or straight from the casters in fixed memory\n"
    "  --fit view|scene what each map covers: the casters the camera sees, or the whole scene\n"
    "  --filter F       point | bilinear | trilinear (trilinear builds the mip chain)\n"
    "  --kernel K       none | box | gaussian: soft surface shadows over curves at texel centres\n"
    "  --kernel-radius R  the kernel's radius in texels, 1 to 4 (box: 2R + 1 wide; gaussian: sigma R / 2)\n"
    "  --shadow-res R   transmittance map texels per side (of each map: cube face, cascade, cluster)\n"
    "  --shadow-layout dense|paged  dense maps rebuilt every frame, or paged virtual maps whose\n"
    "                   pages the camera's receivers ask for, built once into a fixed pool\n"
    "  --virtual-res R  paged: the virtual map's texels per side, a power of two, 256 to 16384\n"
    "                   (to 262144 for directional lights, whose finest levels follow the camera)\n"
    "  --page-size P    paged: texels per page side, 32, 64 or 128\n"
    "  --virtual-lights K\n"
    "                   every area light's virtual lights (1 to 256; their soft shadows)\n"
    "  --page-pool-mib M  paged: each light's page pool\n"
    "  --page-builds N  paged: build at most N pages a frame, as the viewer does (default: a\n"
    "                   capture builds every page asked for at once); frames are rendered\n"
    "                   again until every page asked for is built\n"
    "  --cascades N     directional lights (only): maps split along the camera's view, 1 to 4\n"
    "  --clusters N     directional and spot lights (not point): casters grouped by their\n"
    "                   light-space bounds, at most N maps (up to 8) of the shadow resolution\n"
    "                   each; 1: off; 0: the scene's \"shadows\" clusters. Not with --cascades > 1\n"
    "  --shadow-param NAME=NUMBER   (repeatable) a technique parameter (listed at the end)\n"
    "  --interpolation linear|exponential   between AVSM nodes (default linear)\n"
    "  --probe FILE     JSON array [[x,y,z],...]: writes probes.json with each light's\n"
    "                   transmittance at every point\n"
    "  --flicker        flicker.json: per light, how much its transmittance changes from frame\n"
    "                   to frame at the surfaces the first frame sees (with --orbit, or a shot\n"
    "                   where only the camera moves)\n"
    "shadow quality against the exact reference (keeps every light's capture lists):\n"
    "  --compare-to uncompressed   per light, |T - T_exact| at the surfaces and smoke the\n"
    "                   camera sees: quality.json and light<i>_error.png (error x4)\n"
    "  --measure-resolution  per light, how wide on screen the texels that the surfaces' lookups\n"
    "                   read are (at most 1.5 pixels: matched): resolution.json and\n"
    "                   light<i>_resolution.png\n"
    "  --plot-texel LIGHT:X,Y      (repeatable) LIGHT: index or name; X,Y: level-0 texel\n"
    "                   (y = 0 at the bottom of light<i>_transmittance.png): writes\n"
    "                   curve_<light index>_<x>_<y>.svg, the technique's curve over the exact one\n"
    "  --dump-passes FILE  write the first frame's shadow pass list (passes, resources,\n"
    "                   usages, sizes: what a host's frame graph schedules) as JSON and\n"
    "                   stop without rendering\n"
    "  --list-techniques   the shadow techniques' names, one per line\n"
    "  --help           this text\n";

[[noreturn]] void usage_error(const std::string& message) { throw UsageError(message); }

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

// `value` through a `*_from_string` function, or a usage error listing what the flag takes.
template <class FromString>
auto parse_choice(const std::string& flag, const std::string& value, FromString from_string, const char* expected) {
  const auto parsed = from_string(value);
  if (!parsed) usage_error(flag + " expects " + expected + ", got '" + value + "'");
  return *parsed;
}

// The whole of `text` as a finite number, or nullopt.
template <class Number>
std::optional<Number> parse_number(const std::string& text) {
  try {
    size_t used = 0;
    const Number n = std::is_same_v<Number, float> ? std::stof(text, &used) : std::stod(text, &used);
    if (used == text.size() && std::isfinite(n)) return n;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

// The shortest text that reads back as exactly `value` (std::to_chars' guarantee).
template <class Number>
std::string exact_text(Number value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

void parse_shadow_param(const std::string& text, scene::ShadowOverrides& shadow) {
  const size_t equals = text.find('=');
  const std::optional<double> number =
      equals == std::string::npos || equals == 0 ? std::nullopt : parse_number<double>(text.substr(equals + 1));
  if (!number)
    usage_error("--shadow-param expects NAME=NUMBER (e.g. error=0.01, slices=32, terms=16), got '" + text + "'");
  shadow.parameters[text.substr(0, equals)] = *number;
}

// One flag (with its value, read through `value`) into `options`; false: not a known flag.
bool parse_option(const std::string& arg, const std::function<std::string()>& value, CaptureOptions& options) {
  if (arg == "--scene") {
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
    options.frames_in_flight = uint32_t(parse_in_range(arg, value(), 1, 3));
  } else if (arg == "--time") {
    const std::string text = value();
    const std::optional<float> seconds = parse_number<float>(text);
    if (!seconds || !std::isfinite(*seconds)) usage_error("--time expects a number of seconds, got '" + text + "'");
    options.time = *seconds;
  } else if (arg == "--frame-range") {
    const std::string text = value();
    FrameRange range = options.frame_range.value_or(FrameRange{});
    if (!parse_frame_range(text, range)) usage_error("--frame-range expects A:B with 0 <= A <= B, got '" + text + "'");
    options.frame_range = range;
  } else if (arg == "--fps") {
    const std::string text = value();
    const std::optional<float> fps = parse_number<float>(text);
    if (!fps || !(*fps > 0.0f && *fps <= 1000.0f)) usage_error("--fps expects a frame rate in (0, 1000], got '" + text + "'");
    options.fps = *fps;
  } else if (arg == "--orbit") {
    const std::string text = value();
    const std::optional<float> degrees = parse_number<float>(text);
    if (!degrees || !(std::abs(*degrees) <= 90.0f)) usage_error("--orbit expects -90 to 90 degrees per frame, got '" + text + "'");
    options.orbit_degrees = *degrees;
  } else if (arg == "--light-orbit") {
    const std::string text = value();
    const std::optional<float> degrees = parse_number<float>(text);
    if (!degrees || !(std::abs(*degrees) <= 90.0f))
      usage_error("--light-orbit expects -90 to 90 degrees per frame, got '" + text + "'");
    options.light_orbit_degrees = *degrees;
  } else if (arg == "--device") {
    options.device = value();
  } else if (arg == "--validation") {
    options.validation = true;
  } else if (arg == "--quiet") {
    options.progress = false;
  } else if (arg == "--report") {
    options.report = true;
  } else if (arg == "--volume-shading") {
    options.volume_shading.mode =
        parse_choice(arg, value(), scene::volume_shading_mode_from_string, "fast, reference or hidden");
  } else if (arg == "--volume-resolution-divisor") {
    const uint32_t n = parse_count(arg, value());
    if (n != 1 && n != 2 && n != 4) usage_error("--volume-resolution-divisor expects 1, 2 or 4");
    options.volume_shading.resolution_divisor = int(n);
  } else if (arg == "--volume-step") {
    const std::string text = value();
    const std::optional<float> voxels = parse_number<float>(text);
    if (!voxels) usage_error("--volume-step expects a number of voxels, got '" + text + "'");
    if (!(*voxels >= 0.125f && *voxels <= 4.0f)) usage_error("--volume-step expects 0.125 to 4 voxels");
    options.volume_shading.step_voxels = *voxels;
  } else if (arg == "--compare-volume-shading") {
    options.compare_volume_shading = true;
  } else if (arg == "--path-trace-volumes") {
    const uint32_t n = parse_count(arg, value());
    if (n < 1 || n > 4096) usage_error("--path-trace-volumes expects 1 to 4096 paths per pixel");
    options.path_trace_volumes = int(n);
  } else if (arg == "--volume-octaves") {
    const uint32_t n = parse_count(arg, value());
    if (n < 1 || n > 8) usage_error("--volume-octaves expects 1 (single scattering) to 8");
    options.volume_octaves = int(n);
  } else if (arg == "--sky-light") {
    const std::string text = value();
    const std::optional<float> share = parse_number<float>(text);
    if (!share || !(*share >= 0.0f && *share <= 4.0f)) usage_error("--sky-light expects 0 to 4, got '" + text + "'");
    options.volume_sky_light = *share;
  } else if (arg == "--fog") {
    const std::string text = value();
    if (text != "on" && text != "off") usage_error("--fog expects on or off, got '" + text + "'");
    options.fog = text == "on";
  } else if (arg == "--area-shadows") {
    const std::string text = value();
    if (text != "filtered" && text != "exact")
      usage_error("--area-shadows expects filtered or exact, got '" + text + "'");
    options.area_shadows_filtered = text == "filtered";
  } else if (arg == "--compare-fog") {
    options.compare_fog = true;
  } else if (arg == "--technique") {
    const std::string name = value();
    if (!passes::find_shadow_technique(name))
      usage_error("--technique expects one of " + passes::shadow_technique_names() + ", got '" + name + "'");
    options.shadow.technique = name;
  } else if (arg == "--nodes") {
    const uint32_t n = parse_count(arg, value());
    if (n != 4 && n != 8 && n != 12 && n != 16) usage_error("--nodes expects 4, 8, 12 or 16");
    options.shadow.nodes = int(n);
  } else if (arg == "--sort") {
    options.shadow.sort = parse_on_off(arg, value());
  } else if (arg == "--build") {
    options.shadow.build = parse_choice(arg, value(), scene::shadow_build_from_string, "lists or fixed");
  } else if (arg == "--fit") {
    options.shadow.fit = parse_choice(arg, value(), scene::shadow_fit_from_string, "view or scene");
  } else if (arg == "--filter") {
    options.shadow.filter = parse_choice(arg, value(), scene::shadow_filter_from_string, "point, bilinear or trilinear");
  } else if (arg == "--kernel") {
    options.shadow.kernel = parse_choice(arg, value(), scene::shadow_kernel_from_string, "none, box or gaussian");
  } else if (arg == "--kernel-radius") {
    options.shadow.kernel_radius = parse_in_range(arg, value(), 1, 4);
  } else if (arg == "--shadow-layout") {
    options.shadow.layout = parse_choice(arg, value(), scene::shadow_layout_from_string, "dense or paged");
  } else if (arg == "--virtual-res") {
    const uint32_t r = parse_count(arg, value());
    if (r < 256 || r > 262144 || (r & (r - 1)) != 0) usage_error("--virtual-res expects a power of two, 256 to 262144");
    options.shadow.virtual_resolution = int(r);
  } else if (arg == "--virtual-lights") {
    options.shadow.virtual_lights = parse_in_range(arg, value(), 1, scene::kMaxVirtualLights);
  } else if (arg == "--page-size") {
    const uint32_t p = parse_count(arg, value());
    if (p != 32 && p != 64 && p != 128) usage_error("--page-size expects 32, 64 or 128");
    options.shadow.page_size = int(p);
  } else if (arg == "--page-pool-mib") {
    const uint32_t m = parse_count(arg, value());
    if (m > 4096) usage_error("--page-pool-mib expects at most 4096");
    options.shadow.page_pool_mib = double(m);
  } else if (arg == "--page-builds") {
    options.shadow.page_builds_per_frame = parse_in_range(arg, value(), 0, 65536);
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
  } else if (arg == "--dump-passes") {
    options.dump_passes = value();
  } else if (arg == "--probe") {
    options.probe_file = value();
  } else if (arg == "--flicker") {
    options.flicker = true;
  } else if (arg == "--shadow-param") {
    parse_shadow_param(value(), options.shadow);
  } else if (arg == "--compare-to") {
    const std::string name = value();
    if (name != "uncompressed")
      usage_error("--compare-to expects uncompressed (the exact reference), got '" + name + "'");
    options.compare_to_uncompressed = true;
  } else if (arg == "--measure-resolution") {
    options.measure_resolution = true;
  } else if (arg == "--plot-texel") {
    const std::string spec = value();
    std::optional<TexelPlot> plot = parse_texel_plot(spec);
    if (!plot) usage_error("--plot-texel expects LIGHT:X,Y (light index or name, level-0 texel), got '" + spec + "'");
    options.plot_texels.push_back(*plot);
  } else {
    return false;
  }
  return true;
}

}  // namespace

CaptureCommand parse_capture_arguments(const std::vector<std::string>& args) {
  CaptureCommand command;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h") return {CaptureAction::help, {}};
    if (arg == "--list-techniques") return {CaptureAction::list_techniques, {}};
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) usage_error(arg + " needs a value");
      return args[++i];
    };
    if (!parse_option(arg, value, command.options)) usage_error("unknown option '" + arg + "'");
  }
  // A light is either cascaded or clustered (both split it into maps of their own kind).
  const scene::ShadowOverrides& shadow = command.options.shadow;
  if (shadow.cascades.value_or(1) > 1 && shadow.clusters.value_or(0) > 1)
    usage_error("--cascades and --clusters exclude each other: a light's maps are either cascades or clusters");
  if (command.options.compare_fog && command.options.fog == false)
    usage_error("--compare-fog needs the fog on (drop --fog off)");
  CaptureOptions& o = command.options;
  if (o.frame_range) {
    o.frame_range->fps = o.fps;
    if (o.time) usage_error("--time and --frame-range exclude each other: a shot's frames set their own times");
    if (o.orbit_degrees != 0.0f || o.light_orbit_degrees != 0.0f)
      usage_error("--orbit and --light-orbit turn things per repeated frame; a shot (--frame-range) moves them by the scene's animation");
  } else if (o.fps != CaptureOptions{}.fps) {
    usage_error("--fps needs --frame-range (the shot it sets the rate of)");
  }
  if (o.flicker && !o.probe_file.empty())
    usage_error("--flicker and --probe exclude each other: both are read through the probe pass");
  if (o.flicker && o.light_orbit_degrees != 0.0f)
    usage_error("--flicker needs the lights to hold still (drop --light-orbit): it measures what the camera's motion alone changes");
  if (command.options.path_trace_volumes > 0 && !command.options.compare_volume_shading)
    usage_error("--path-trace-volumes needs --compare-volume-shading (it compares with the frames that renders)");
  return command;
}

std::vector<std::string> capture_arguments(const CaptureOptions& o) {
  const CaptureOptions defaults;
  std::vector<std::string> args;
  auto flag = [&](bool set, const char* name) {
    if (set) args.push_back(name);
  };
  auto with_value = [&](bool set, const char* name, const std::string& value) {
    if (set) args.insert(args.end(), {name, value});
  };
  with_value(o.scene != defaults.scene, "--scene", o.scene.string());
  with_value(o.camera != defaults.camera, "--camera", o.camera);
  with_value(o.out_dir != defaults.out_dir, "--out", o.out_dir.string());
  with_value(o.width != defaults.width, "--width", std::to_string(o.width));
  with_value(o.height != defaults.height, "--height", std::to_string(o.height));
  with_value(o.frames != defaults.frames, "--frames", std::to_string(o.frames));
  with_value(o.frames_in_flight != defaults.frames_in_flight, "--frames-in-flight", std::to_string(o.frames_in_flight));
  with_value(o.time.has_value(), "--time", o.time ? exact_text(*o.time) : "");
  if (o.frame_range) {
    with_value(true, "--frame-range", std::to_string(o.frame_range->first) + ":" + std::to_string(o.frame_range->last));
    with_value(o.fps != defaults.fps, "--fps", exact_text(o.fps));
  }
  with_value(o.orbit_degrees != defaults.orbit_degrees, "--orbit", exact_text(o.orbit_degrees));
  with_value(o.light_orbit_degrees != defaults.light_orbit_degrees, "--light-orbit", exact_text(o.light_orbit_degrees));
  with_value(o.device != defaults.device, "--device", o.device);
  flag(o.validation, "--validation");
  flag(!o.progress, "--quiet");
  flag(o.report, "--report");

  const scene::VolumeShadingOverrides& volume = o.volume_shading;
  if (volume.mode) with_value(true, "--volume-shading", scene::to_string(*volume.mode));
  if (volume.resolution_divisor) with_value(true, "--volume-resolution-divisor", std::to_string(*volume.resolution_divisor));
  if (volume.step_voxels) with_value(true, "--volume-step", exact_text(*volume.step_voxels));
  flag(o.compare_volume_shading, "--compare-volume-shading");
  with_value(o.path_trace_volumes != defaults.path_trace_volumes, "--path-trace-volumes",
             std::to_string(o.path_trace_volumes));
  if (o.volume_octaves) with_value(true, "--volume-octaves", std::to_string(*o.volume_octaves));
  if (o.volume_sky_light) with_value(true, "--sky-light", exact_text(*o.volume_sky_light));
  if (o.fog) with_value(true, "--fog", *o.fog ? "on" : "off");
  if (o.area_shadows_filtered) with_value(true, "--area-shadows", *o.area_shadows_filtered ? "filtered" : "exact");
  flag(o.compare_fog, "--compare-fog");

  const scene::ShadowOverrides& shadow = o.shadow;
  if (shadow.technique) with_value(true, "--technique", *shadow.technique);
  if (shadow.nodes) with_value(true, "--nodes", std::to_string(*shadow.nodes));
  if (shadow.sort) with_value(true, "--sort", *shadow.sort ? "on" : "off");
  if (shadow.build) with_value(true, "--build", std::string(scene::to_string(*shadow.build)));
  if (shadow.fit) with_value(true, "--fit", std::string(scene::to_string(*shadow.fit)));
  if (shadow.filter) with_value(true, "--filter", std::string(scene::to_string(*shadow.filter)));
  if (shadow.kernel) with_value(true, "--kernel", std::string(scene::to_string(*shadow.kernel)));
  if (shadow.kernel_radius) with_value(true, "--kernel-radius", std::to_string(*shadow.kernel_radius));
  if (shadow.resolution) with_value(true, "--shadow-res", std::to_string(*shadow.resolution));
  if (shadow.layout) with_value(true, "--shadow-layout", std::string(scene::to_string(*shadow.layout)));
  if (shadow.virtual_resolution) with_value(true, "--virtual-res", std::to_string(*shadow.virtual_resolution));
  if (shadow.page_size) with_value(true, "--page-size", std::to_string(*shadow.page_size));
  if (shadow.virtual_lights) with_value(true, "--virtual-lights", std::to_string(*shadow.virtual_lights));
  if (shadow.page_pool_mib) with_value(true, "--page-pool-mib", std::to_string(int(*shadow.page_pool_mib)));
  if (shadow.page_builds_per_frame) with_value(true, "--page-builds", std::to_string(*shadow.page_builds_per_frame));
  if (shadow.cascades) with_value(true, "--cascades", std::to_string(*shadow.cascades));
  if (shadow.clusters) with_value(true, "--clusters", std::to_string(*shadow.clusters));
  for (const auto& [name, value] : shadow.parameters) with_value(true, "--shadow-param", name + "=" + exact_text(value));
  with_value(o.exponential_interpolation, "--interpolation", "exponential");
  with_value(!o.probe_file.empty(), "--probe", o.probe_file.string());
  flag(o.flicker, "--flicker");
  with_value(o.compare_to_uncompressed, "--compare-to", "uncompressed");
  flag(o.measure_resolution, "--measure-resolution");
  for (const TexelPlot& plot : o.plot_texels) with_value(true, "--plot-texel", plot.spec);
  with_value(!o.dump_passes.empty(), "--dump-passes", o.dump_passes.string());
  return args;
}

void validate_capture_options(const CaptureOptions& options) {
  const CaptureCommand parsed = parse_capture_arguments(capture_arguments(options));
  // Values the command line cannot carry (a plot whose spec does not say its texel).
  if (!(parsed.options == options)) throw UsageError("options that avsm-capture's command line cannot express");
}

std::string capture_usage() {
  return std::string(kUsage) + "shadow techniques (--technique) and their parameters (--shadow-param):\n" +
         passes::shadow_technique_help(2);
}

}  // namespace avsm::capture
