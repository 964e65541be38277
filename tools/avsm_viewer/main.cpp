// avsm-viewer: a window on a scene with live shadow settings, GPU timings and
// texel inspection (engine/viewer). This file only parses arguments.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "passes/frame/frames_in_flight.h"
#include "viewer/viewer_app.h"
#include "viewer/window.h"

namespace {

const char* kUsage =
    "usage: avsm-viewer [options]\n"
    "  --scene FILE       scene JSON (default: the generated default scene)\n"
    "  --size WxH         window size (default 1280x720); the panel is docked at the left,\n"
    "                     min(420, 40% of the width) wide, and the scene renders beside it\n"
    "  --device NAME      Vulkan device: index or part of its name (env AVSM_DEVICE)\n"
    "  --validation       Vulkan validation + synchronization validation; any message\n"
    "                     makes the exit status 1\n"
    "  --frames-in-flight N   frames recorded ahead of the GPU, 1 to 3 (default 2)\n"
    "  --out DIR          where the screenshot key (F12 or P) writes shot-NNN/ (default out/viewer)\n"
    "  --volume-shading fast|reference|hidden   as in avsm-capture (default: the scene's)\n"
    "  --volume-resolution-divisor 1|2|4   fast march resolution: 1/N per axis\n"
    "scripted runs (tests, CI):\n"
    "  --frames N         render N scene frames, then exit\n"
    "  --screenshot DIR   after the last frame, write what avsm-capture writes for one\n"
    "                     frame (frame.png, frame.exr, timings.json, ...: the view), window.png\n"
    "                     (the whole window) and layout.json (where the panel and view lie)\n"
    "  --inspect X,Y      click pixel (X, Y) of the view first (x right, y down, a pixel of\n"
    "                     frame.png, not of the window); writes inspect.json\n"
    "                     (each light's curve through that point, technique and exact)\n"
    "                     into the --screenshot folder (else --out)\n"
    "  --control          take commands on stdin, one per line, and answer each with a\n"
    "                     JSON line on stdout: frame | inspect X,Y | screenshot DIR |\n"
    "                     light I FIELD VALUE | exposure V | quit (engine/viewer/control_commands.h)\n"
    "keys (over the view): left drag orbit, right drag pan (fly: look), wheel zoom,\n"
    "      WASDQE fly, click inspect a texel, F12/P screenshot, Esc quit\n"
    "  --help             this text\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "avsm-viewer: %s\n%s", message.c_str(), kUsage);
  std::exit(2);
}

uint32_t parse_positive(const std::string& flag, const std::string& text) {
  try {
    size_t used = 0;
    const long long n = std::stoll(text, &used);
    if (used == text.size() && n >= 1 && n <= 100000) return uint32_t(n);
  } catch (const std::exception&) {
  }
  usage_error(flag + " expects a positive whole number, got '" + text + "'");
}

// "A<sep>B" as two numbers checked by `parse`.
template <class Parse>
auto parse_pair(const std::string& flag, const std::string& text, char separator, const char* shape, Parse parse) {
  const size_t at = text.find(separator);
  if (at == std::string::npos) usage_error(flag + " expects " + shape + ", got '" + text + "'");
  return std::make_pair(parse(text.substr(0, at)), parse(text.substr(at + 1)));
}

}  // namespace

int main(int argc, char** argv) {
  avsm::viewer::ViewerOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf("%s", kUsage);
      return 0;
    } else if (arg == "--scene") {
      options.scene = value();
    } else if (arg == "--size") {
      const std::string text = value();
      const auto [w, h] = parse_pair(arg, text, 'x', "WxH", [&](const std::string& n) {
        const uint32_t v = parse_positive(arg, n);
        if (v > 16384) usage_error("--size: at most 16384 pixels per side, got '" + text + "'");
        return v;
      });
      options.width = w;
      options.height = h;
    } else if (arg == "--device") {
      options.device = value();
    } else if (arg == "--frames-in-flight") {
      const std::string text = value();
      options.frames_in_flight = parse_positive(arg, text);
      if (options.frames_in_flight > avsm::passes::kMaxFramesInFlight)
        usage_error("--frames-in-flight expects 1 to " + std::to_string(avsm::passes::kMaxFramesInFlight) + ", got '" + text + "'");
    } else if (arg == "--validation") {
      options.validation = true;
    } else if (arg == "--out") {
      options.out_dir = value();
    } else if (arg == "--frames") {
      options.frames = parse_positive(arg, value());
    } else if (arg == "--volume-shading") {
      const std::string name = value();
      options.volume_shading.mode = avsm::scene::volume_shading_mode_from_string(name);
      if (!options.volume_shading.mode)
        usage_error("--volume-shading expects fast, reference or hidden, got '" + name + "'");
    } else if (arg == "--volume-resolution-divisor") {
      const uint32_t n = parse_positive(arg, value());
      if (n != 1 && n != 2 && n != 4) usage_error("--volume-resolution-divisor expects 1, 2 or 4");
      options.volume_shading.resolution_divisor = int(n);
    } else if (arg == "--control") {
      options.control = true;
    } else if (arg == "--screenshot") {
      options.screenshot_dir = value();
    } else if (arg == "--inspect") {
      const std::string text = value();
      const auto [x, y] = parse_pair(arg, text, ',', "X,Y pixel coordinates", [&](const std::string& n) {
        try {
          size_t used = 0;
          const long v = std::stol(n, &used);
          if (used == n.size() && v >= 0) return float(v);
        } catch (const std::exception&) {
        }
        usage_error("--inspect expects X,Y pixel coordinates, got '" + text + "'");
      });
      options.inspect_pixel = glm::vec2(x, y);
    } else {
      usage_error("unknown option '" + arg + "'");
    }
  }
  if (!options.screenshot_dir.empty() && options.frames == 0)
    usage_error("--screenshot needs --frames N (the screenshot is taken after the last frame)");
  if (options.inspect_pixel && options.frames == 0) usage_error("--inspect needs --frames N");
  if (options.control && options.frames > 0) usage_error("--control and --frames do not mix: send 'frame' commands");

  try {
    return avsm::viewer::run_viewer(options);
  } catch (const avsm::viewer::WindowError& e) {
    std::fprintf(stderr, "avsm-viewer: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avsm-viewer: %s\n", e.what());
    return 1;
  }
}
