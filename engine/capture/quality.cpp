#include "capture/quality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>
#include <sstream>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/resources.h"
#include "capture/files.h"
#include "capture/frame_report.h"
#include "capture/html.h"
#include "io/image_io.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/shadows/techniques/techniques.h"

namespace avsm::capture {
namespace fs = std::filesystem;

void write_pixel_image(const fs::path& path, uint32_t width, uint32_t height,
                       const std::function<void(size_t pixel, float* rgb)>& colour) {
  gpu::ImageRGBA32F image;
  image.width = width;
  image.height = height;
  image.pixels.assign(size_t(width) * height * 4, 1.0f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) colour(size_t(y) * width + x, image.at(x, y));
  io::write_png_raw(path, image);
}

std::string light_label(const scene::Scene& scene, size_t index) {
  const std::string& name = scene.lights[index].name;
  return name.empty() ? "light " + std::to_string(index) : name;
}

namespace {

// Black (no error) -> red -> yellow -> white (error >= 1/kErrorImageScale).
void heat_colour(float error, float* rgb) {
  const float e = std::clamp(error * kErrorImageScale, 0.0f, 1.0f);
  rgb[0] = std::clamp(3.0f * e, 0.0f, 1.0f);
  rgb[1] = std::clamp(3.0f * e - 1.0f, 0.0f, 1.0f);
  rgb[2] = std::clamp(3.0f * e - 2.0f, 0.0f, 1.0f);
}

void write_error_image(const fs::path& path, const passes::PixelShadowError* errors, uint32_t width,
                       uint32_t height) {
  write_pixel_image(path, width, height, [&](size_t pixel, float* rgb) {
    const passes::PixelShadowError& e = errors[pixel];
    const bool surface = e.surface >= 0.0f, smoke = e.smoke_count > 0.0f;
    if (!surface && !smoke)
      std::copy(kNoReceiverColour, kNoReceiverColour + 3, rgb);
    else
      heat_colour(std::max(surface ? e.surface : 0.0f, smoke ? e.smoke_max : 0.0f), rgb);
  });
}

std::optional<uint32_t> parse_uint(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return uint32_t(std::stoul(text));
}

// ---- SVG ----


std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", v);
  return buffer;
}

std::string tick_label(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", std::abs(v) < 1e-9 ? 0.0 : v);
  return buffer;
}

// A 1-2-5 step giving about `count` intervals over `range`.
double nice_step(double range, int count) {
  const double raw = range / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * magnitude) return m * magnitude;
  return 10.0 * magnitude;
}


// `count` vec4s from vec4 `first` on of a light's map, through a small staging buffer. The
// copy is a graph pass: the map comes in the state the frames left it in, the staging
// buffer leaves in host-read state, and the graph plans the barriers in between.
std::vector<glm::vec4> read_map_vec4s(gpu::Context& ctx, const gpu::Buffer& map, uint64_t first, uint64_t count) {
  const VkDeviceSize bytes = count * sizeof(glm::vec4);
  gpu::Buffer stage = gpu::Buffer::create(
      ctx, {bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryLocation::HostReadback, "texel nodes readback"});
  rg::Graph graph;
  const rg::ImportState after_frame = passes::ShadowMaps::map_state_after_frame();
  const rg::BufferHandle source = rg::vulkan::import(graph, "shadow map", map, after_frame, after_frame);
  const rg::BufferHandle target =
      rg::vulkan::import(graph, "texel nodes readback", stage, rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  const VkBufferCopy region{first * sizeof(glm::vec4), 0, bytes};
  graph.add_pass("read texel nodes", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b) {
        b.read(source, rg::Usage::TransferSrc, {region.srcOffset, bytes});
        b.write(target, rg::Usage::TransferDst);
      },
      [&](rg::PassContext& c) {
        VkBufferCopy copy = region;
        copy.srcOffset += c.buffer(source).offset;  // the map is a region of the shadow map atlas
        vkCmdCopyBuffer(c.cmd(), c.buffer(source), c.buffer(target), 1, &copy);
      });
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact, /*timed_passes=*/1);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
  std::vector<glm::vec4> out(count);
  std::memcpy(out.data(), stage.mapped(), bytes);
  return out;
}

// Sample k of kCurveSamples: evenly over the light's depth range, near to far.
float curve_depth(const passes::LightView& view, uint32_t k) {
  const float f = float(k) / float(kCurveSamples - 1);
  return view.near_depth + f * (view.far_depth - view.near_depth);
}

struct CurvePlot {
  std::string title, technique, description;
  float near_depth = 0, far_depth = 1;
  std::vector<float> depths, technique_values, reference_values;
  std::vector<CurveNode> nodes;
};

std::string curve_svg(const CurvePlot& plot) {
  const double width = 720, height = 440, left = 70, right = 24, top = 58, bottom = 56;
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  const double x0 = plot.near_depth, x1 = std::max(plot.far_depth, plot.near_depth + 1e-6f);
  auto px = [&](double d) { return left + (d - x0) / (x1 - x0) * plot_w; };
  auto py = [&](double t) { return top + (1.0 - std::clamp(t, -0.05, 1.05)) * plot_h; };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\"" << num(height)
      << "\" viewBox=\"0 0 " << num(width) << " " << num(height) << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<title>" << escape_markup(plot.title) << "</title>\n<desc>" << escape_markup(plot.description) << "</desc>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << num(width / 2) << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
      << escape_markup(plot.title) << "</text>\n";
  // Largest gap between the curves, as a subtitle.
  double max_gap = 0;
  for (size_t i = 0; i < plot.depths.size(); ++i)
    max_gap = std::max(max_gap, double(std::abs(plot.technique_values[i] - plot.reference_values[i])));
  svg << "<text x=\"" << num(width / 2) << "\" y=\"40\" text-anchor=\"middle\" fill=\"#555\">max |T - T_exact| "
      << "along the texel: " << tick_label(std::round(max_gap * 1e4) / 1e4) << "</text>\n";

  // Grid, ticks and labels.
  svg << "<g stroke=\"#ddd\" stroke-width=\"1\">\n";
  const double step = nice_step(x1 - x0, 6);
  std::vector<double> x_ticks;
  for (double d = std::ceil(x0 / step) * step; d <= x1 + step * 1e-6; d += step) x_ticks.push_back(d);
  for (double d : x_ticks)
    svg << "<line x1=\"" << num(px(d)) << "\" y1=\"" << num(top) << "\" x2=\"" << num(px(d)) << "\" y2=\""
        << num(top + plot_h) << "\"/>\n";
  for (int i = 0; i <= 4; ++i)
    svg << "<line x1=\"" << num(left) << "\" y1=\"" << num(py(i * 0.25)) << "\" x2=\"" << num(left + plot_w)
        << "\" y2=\"" << num(py(i * 0.25)) << "\"/>\n";
  svg << "</g>\n<g fill=\"#333\">\n";
  for (double d : x_ticks)
    svg << "<text x=\"" << num(px(d)) << "\" y=\"" << num(top + plot_h + 18) << "\" text-anchor=\"middle\">"
        << tick_label(d) << "</text>\n";
  for (int i = 0; i <= 4; ++i)
    svg << "<text x=\"" << num(left - 8) << "\" y=\"" << num(py(i * 0.25) + 4) << "\" text-anchor=\"end\">"
        << tick_label(i * 0.25) << "</text>\n";
  svg << "<text x=\"" << num(left + plot_w / 2) << "\" y=\"" << num(height - 12)
      << "\" text-anchor=\"middle\">light-space depth (world units)</text>\n"
      << "<text transform=\"translate(18 " << num(top + plot_h / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">transmittance</text>\n</g>\n"
      << "<rect x=\"" << num(left) << "\" y=\"" << num(top) << "\" width=\"" << num(plot_w) << "\" height=\""
      << num(plot_h) << "\" fill=\"none\" stroke=\"#333\"/>\n";

  auto polyline = [&](const std::vector<float>& values, const char* id, const char* colour, const char* stroke_width,
                      const char* dash) {
    svg << "<polyline id=\"" << id << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"" << stroke_width
        << "\"" << (dash[0] ? std::string(" stroke-dasharray=\"") + dash + "\"" : std::string()) << " points=\"";
    for (size_t i = 0; i < values.size(); ++i)
      svg << (i ? " " : "") << num(px(plot.depths[i])) << "," << num(py(values[i]));
    svg << "\"/>\n";
  };
  polyline(plot.reference_values, "exact", "#222", "2.5", "");
  polyline(plot.technique_values, "technique", "#d62728", "1.5", "6 3");
  for (const CurveNode& n : plot.nodes)
    if (n.depth >= x0 && n.depth <= x1)
      svg << "<circle class=\"node\" cx=\"" << num(px(n.depth)) << "\" cy=\"" << num(py(n.transmittance))
          << "\" r=\"3.5\" fill=\"#d62728\"/>\n";

  // Legend: in the corner of the plot the curves cross least.
  const double legend_w = 220, legend_h = plot.nodes.empty() ? 48 : 66;
  const double corners[4][2] = {{left + plot_w - legend_w - 10, top + 12},
                                {left + 10, top + plot_h - legend_h - 12},
                                {left + plot_w - legend_w - 10, top + plot_h - legend_h - 12},
                                {left + 10, top + 12}};
  size_t best = 0, best_hits = SIZE_MAX;
  for (size_t c = 0; c < 4; ++c) {
    size_t hits = 0;
    for (size_t i = 0; i < plot.depths.size(); ++i)
      for (float t : {plot.technique_values[i], plot.reference_values[i]}) {
        const double x = px(plot.depths[i]), y = py(t);
        hits += x >= corners[c][0] - 4 && x <= corners[c][0] + legend_w + 4 && y >= corners[c][1] - 4 &&
                y <= corners[c][1] + legend_h + 4;
      }
    if (hits < best_hits) best = c, best_hits = hits;
  }
  const double lx = corners[best][0], ly = corners[best][1];
  svg << "<g id=\"legend\">\n<rect x=\"" << num(lx) << "\" y=\"" << num(ly) << "\" width=\"" << num(legend_w)
      << "\" height=\"" << num(legend_h) << "\" fill=\"white\" fill-opacity=\"0.9\" stroke=\"#999\"/>\n"
      << "<line x1=\"" << num(lx + 10) << "\" y1=\"" << num(ly + 16) << "\" x2=\"" << num(lx + 40) << "\" y2=\""
      << num(ly + 16) << "\" stroke=\"#222\" stroke-width=\"2.5\"/>\n"
      << "<text x=\"" << num(lx + 48) << "\" y=\"" << num(ly + 20) << "\">exact (uncompressed)</text>\n"
      << "<line x1=\"" << num(lx + 10) << "\" y1=\"" << num(ly + 34) << "\" x2=\"" << num(lx + 40) << "\" y2=\""
      << num(ly + 34) << "\" stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"6 3\"/>\n"
      << "<text x=\"" << num(lx + 48) << "\" y=\"" << num(ly + 38) << "\">" << escape_markup(plot.technique)
      << "</text>\n";
  if (!plot.nodes.empty())
    svg << "<circle cx=\"" << num(lx + 25) << "\" cy=\"" << num(ly + 52) << "\" r=\"3.5\" fill=\"#d62728\"/>\n"
        << "<text x=\"" << num(lx + 48) << "\" y=\"" << num(ly + 56) << "\">stored nodes</text>\n";
  svg << "</g>\n</svg>\n";
  return svg.str();
}

}  // namespace

std::string technique_label(const scene::ShadowSettings& s) {
  return passes::shadow_technique(s.technique).label(s);
}

// The stored AVSM nodes of a level-0 texel (padding repeats of the last node dropped);
// none for lights that are not AVSM.
std::vector<CurveNode> texel_nodes(gpu::Context& ctx, const passes::ShadowMaps& shadows, uint32_t light, uint32_t x,
                                   uint32_t y) {
  const gpu::Buffer& map = shadows.avsm_map(light);
  if (!map || !shadows.technique(light).stores_avsm_nodes()) return {};
  const passes::AvsmMapLayout& layout = shadows.map_layout(light);
  const passes::LightView& view = shadows.light_views().at(light);
  // A paged map's texel: in the page of the finest resident level over it.
  uint64_t first = layout.texel_base(0, x, y);
  if (shadows.is_paged(light)) {
    const std::optional<passes::ShadowMaps::PagedTexel> paged = shadows.paged_texel(light, x, y);
    if (!paged) return {};
    first = paged->map_vec4;
  }
  const std::vector<glm::vec4> curve = read_map_vec4s(ctx, map, first, layout.vec4s_per_texel());
  std::vector<CurveNode> nodes;
  for (uint32_t i = 0; i < layout.nodes; ++i) {
    const passes::AvsmMapLayout::Node stored =
        passes::AvsmMapLayout::node(curve.data(), i, view.near_depth, view.far_depth);
    const CurveNode n{stored.depth, stored.transmittance};
    if (!nodes.empty() && n.depth == nodes.back().depth && n.transmittance == nodes.back().transmittance) continue;
    nodes.push_back(n);
  }
  return nodes;
}

// ---- quality ----

void ErrorStats::add(const ErrorStats& other) {
  receivers += other.receivers;
  sum += other.sum;
  max = std::max(max, other.max);
}

ErrorStats LightQuality::all() const {
  ErrorStats s = surface;
  s.add(smoke);
  s.add(hair);
  return s;
}

std::vector<LightQuality> summarize_quality(const std::vector<passes::PixelShadowError>& errors, uint32_t width,
                                            uint32_t height, const scene::Scene& scene, const HairErrors& hair) {
  const size_t pixels = size_t(width) * height;
  std::vector<LightQuality> lights;
  for (size_t light = 0; light < scene.lights.size(); ++light) {
    LightQuality q;
    q.light = light_label(scene, light);
    q.settings = scene.lights[light].shadow;
    if ((light + 1) * pixels <= errors.size()) {
      for (size_t i = 0; i < pixels; ++i) {
        const passes::PixelShadowError& e = errors[light * pixels + i];
        if (e.surface >= 0.0f) {
          ++q.surface.receivers;
          q.surface.sum += e.surface;
          q.surface.max = std::max(q.surface.max, double(e.surface));
        }
        if (e.smoke_count > 0.0f) {
          q.smoke.receivers += uint64_t(e.smoke_count);
          q.smoke.sum += e.smoke_sum;
          q.smoke.max = std::max(q.smoke.max, double(e.smoke_max));
        }
      }
    }
    if ((light + 1) * size_t(hair.receivers) <= hair.errors.size()) {
      for (size_t r = 0; r < hair.receivers; ++r) {
        const float e = hair.errors[light * hair.receivers + r];
        if (e < 0.0f) continue;
        ++q.hair.receivers;
        q.hair.sum += e;
        q.hair.max = std::max(q.hair.max, double(e));
      }
    }
    lights.push_back(std::move(q));
  }
  return lights;
}

const char* const kErrorImageColours =
    "black: 0, red, yellow, white: error >= 1/scale; dim blue: no receiver for the light in the pixel";

std::string surface_receivers_rule() {
  return "the opaque surface in the depth buffer (normal from the depth buffer, normal offset as the opaque pass), "
         "where the light reaches it: facing the light, inside a spot's cone";
}

std::string smoke_receivers_rule() {
  return std::to_string(passes::ShadowQualityPass::kSmokeSamplesPerVolume) +
         " evenly spaced points per volume of the pixel ray's stretch inside the volume's support, in front of the "
         "surface, where the density is > 0 and the light reaches";
}

std::string hair_receivers_rule() {
  return "strand vertices (every k-th, at most " + std::to_string(passes::ShadowQualityHairPass::kMaxReceivers) +
         ") inside the view and not behind the opaque depth, looked up as the hair pass shades them; hair hidden "
         "behind other hair still counts (hair writes no depth); not in the error images";
}

std::string error_image_name(size_t light) { return "light" + std::to_string(light) + "_error.png"; }

QualityReport write_quality(const fs::path& out_dir, const scene::Scene& scene,
                            const std::vector<passes::PixelShadowError>& errors, uint32_t width, uint32_t height,
                            const HairErrors& hair) {
  QualityReport report{width, height, summarize_quality(errors, width, height, scene, hair)};
  const size_t pixels = size_t(width) * height;
  for (size_t i = 0; i < report.lights.size() && (i + 1) * pixels <= errors.size(); ++i)
    write_error_image(out_dir / error_image_name(i), errors.data() + i * pixels, width, height);
  write_json(out_dir / "quality.json", to_json(report));
  return report;
}

// ---- texel curves ----

std::optional<TexelPlot> parse_texel_plot(const std::string& spec) {
  const size_t colon = spec.rfind(':');
  if (colon == std::string::npos || colon == 0) return std::nullopt;
  const std::string coords = spec.substr(colon + 1);
  const size_t comma = coords.find(',');
  if (comma == std::string::npos) return std::nullopt;
  const std::optional<uint32_t> x = parse_uint(coords.substr(0, comma)), y = parse_uint(coords.substr(comma + 1));
  if (!x || !y) return std::nullopt;
  TexelPlot plot;
  plot.spec = spec;
  plot.light = spec.substr(0, colon);
  plot.x = *x;
  plot.y = *y;
  return plot;
}

void resolve_texel_plots(std::vector<TexelPlot>& plots, const scene::Scene& scene) {
  for (TexelPlot& plot : plots) {
    const std::string flag = "--plot-texel '" + plot.spec + "': ";
    std::optional<size_t> found;
    if (const std::optional<uint32_t> index = parse_uint(plot.light); index && *index < scene.lights.size())
      found = *index;
    for (size_t i = 0; !found && i < scene.lights.size(); ++i)
      if (scene.lights[i].name == plot.light) found = i;
    if (!found) {
      std::string names;
      for (size_t i = 0; i < scene.lights.size(); ++i)
        names += (i ? ", " : "") + std::to_string(i) + " '" + scene.lights[i].name + "'";
      throw std::runtime_error(flag + "the scene has no light '" + plot.light + "'; lights: " +
                               (names.empty() ? "none" : names));
    }
    // A paged light's texels are those of its virtual map's finest level.
    const scene::ShadowSettings& shadow = scene.lights[*found].shadow;
    const bool paged = shadow.layout == scene::ShadowLayout::paged;
    const int resolution = std::max(paged ? shadow.virtual_resolution : shadow.resolution, 1);
    if (plot.x >= uint32_t(resolution) || plot.y >= uint32_t(resolution))
      throw std::runtime_error(flag + "texel (" + std::to_string(plot.x) + ", " + std::to_string(plot.y) +
                               ") is outside light " + std::to_string(*found) + " '" + scene.lights[*found].name +
                               "': its " + (paged ? "virtual " : "") + "map has " + std::to_string(resolution) + "x" +
                               std::to_string(resolution) + " texels (0.." + std::to_string(resolution - 1) + ")");
    plot.light_index = uint32_t(*found);
  }
}

std::vector<passes::TexelSample> texel_curve_samples(const std::vector<TexelPlot>& plots,
                                                     const std::vector<passes::LightView>& views) {
  std::vector<passes::TexelSample> samples;
  for (const TexelPlot& plot : plots) {
    const passes::LightView& view = views.at(plot.light_index);
    for (uint32_t k = 0; k < kCurveSamples; ++k)
      samples.push_back({plot.light_index, {plot.x, plot.y}, curve_depth(view, k)});
  }
  return samples;
}

std::vector<fs::path> write_texel_curves(const fs::path& out_dir, const std::vector<TexelPlot>& plots,
                                         const scene::Scene& scene, const passes::ShadowMaps& shadows,
                                         gpu::Context& ctx, const std::vector<passes::TexelSampleResult>& results) {
  if (results.size() != plots.size() * kCurveSamples)
    throw std::runtime_error("texel curves: " + std::to_string(results.size()) + " results for " +
                             std::to_string(plots.size()) + " curves");
  std::vector<fs::path> files;
  for (size_t p = 0; p < plots.size(); ++p) {
    const TexelPlot& plot = plots[p];
    const passes::LightView& view = shadows.light_views().at(plot.light_index);
    const scene::ShadowSettings& settings = scene.lights[plot.light_index].shadow;
    CurvePlot curve;
    curve.technique = technique_label(settings);
    curve.title = "Light " + std::to_string(plot.light_index) + " '" + light_label(scene, plot.light_index) +
                  "', texel (" + std::to_string(plot.x) + ", " + std::to_string(plot.y) + "): " + curve.technique +
                  " vs exact";
    curve.near_depth = view.near_depth;
    curve.far_depth = view.far_depth;
    for (uint32_t k = 0; k < kCurveSamples; ++k) {
      const passes::TexelSampleResult& r = results[p * kCurveSamples + k];
      curve.depths.push_back(curve_depth(view, k));
      curve.technique_values.push_back(r.technique);
      curve.reference_values.push_back(r.reference);
    }
    curve.nodes = texel_nodes(ctx, shadows, plot.light_index, plot.x, plot.y);
    // The texel's centre ray in world space: light clip z 0 (near depth) to 1 (far depth).
    const float res = float(view.resolution);
    const glm::vec2 ndc((plot.x + 0.5f) / res * 2.0f - 1.0f, (plot.y + 0.5f) / res * 2.0f - 1.0f);
    auto world = [&](float z) {
      const glm::vec4 p = view.world_from_light * glm::vec4(ndc, z, 1.0f);
      return glm::vec3(p) / p.w;
    };
    const glm::vec3 a = world(0.0f), b = world(1.0f);
    char description[512];
    std::snprintf(description, sizeof(description),
                  "%u samples of the texel's level-0 curve over depths %g..%g (no filtering), the texel centre ray "
                  "from world (%g, %g, %g) to (%g, %g, %g); %s; --plot-texel %s",
                  kCurveSamples, view.near_depth, view.far_depth, a.x, a.y, a.z, b.x, b.y, b.z,
                  curve.technique.c_str(), plot.spec.c_str());
    curve.description = description;
    const fs::path path = out_dir / ("curve_" + std::to_string(plot.light_index) + "_" + std::to_string(plot.x) +
                                     "_" + std::to_string(plot.y) + ".svg");
    write_text(path, curve_svg(curve));
    files.push_back(path);
  }
  return files;
}

}  // namespace avsm::capture
