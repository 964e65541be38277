#include "passes/camera/volumes/volume_pass.h"

#include "passes/frame/frame_inputs.h"

#include <nanovdb/NanoVDB.h>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "gpu/device_limits.h"
#include "gpu/transfer.h"
#include "passes/frame/lights.h"
#include "passes/shadows/shadow_maps.h"
#include "scene/volume_scattering.h"
#include "shared/passes/camera/volumes/volume_march.h"

namespace avsm::passes {
namespace {

// NanoVDB grids must start on a 32-byte boundary (NANOVDB_DATA_ALIGNMENT).
constexpr size_t kGridAlignment = 32;
// PNanoVDB in GLSL addresses its buffer with 32-bit byte offsets.
constexpr uint64_t kMaxGridBytes = uint64_t(std::numeric_limits<uint32_t>::max()) + 1;


using Push = shared::VolumeMarchPush;  // shaders/shared/passes/camera/volumes/volume_march.h

std::string label(const scene::Volume& volume, size_t index) {
  return "volume " + std::to_string(index) + (volume.name.empty() ? "" : " '" + volume.name + "'");
}

// The GPU reads the bytes as a NanoVDB float grid through PNanoVDB, which trusts them.
void check_grid(const scene::Volume& volume, size_t index) {
  const std::string who = label(volume, index);
  if (volume.nanovdb.size() < sizeof(nanovdb::GridData))
    throw std::invalid_argument("VolumePass: " + who + " has no NanoVDB grid (" +
                                std::to_string(volume.nanovdb.size()) + " bytes)");
  const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
  if (!grid->isValid()) throw std::invalid_argument("VolumePass: " + who + " does not start with a NanoVDB grid");
  if (grid->gridType() != nanovdb::GridType::Float)
    throw std::invalid_argument("VolumePass: " + who + " holds a " + nanovdb::toStr(grid->gridType()) +
                                " grid; the march reads float density");
  if (grid->gridSize() > volume.nanovdb.size())
    throw std::invalid_argument("VolumePass: " + who + " says its grid has " + std::to_string(grid->gridSize()) +
                                " bytes but only " + std::to_string(volume.nanovdb.size()) + " are there");
}

void check_majorant(const scene::Volume& volume, size_t index) {
  const scene::MajorantGrid& m = volume.majorant;
  const uint64_t bricks = uint64_t(std::max(m.dims.x, 0)) * uint64_t(std::max(m.dims.y, 0)) * uint64_t(std::max(m.dims.z, 0));
  if (bricks == 0 || m.brick_size < 1 || bricks != m.max_density.size())
    throw std::invalid_argument("VolumePass: " + label(volume, index) + " has a malformed majorant grid (" +
                                std::to_string(m.max_density.size()) + " values for " + std::to_string(m.dims.x) +
                                "x" + std::to_string(m.dims.y) + "x" + std::to_string(m.dims.z) + " bricks of " +
                                std::to_string(m.brick_size) + ")");
}

void check_optics(const scene::Volume& volume, size_t index) {
  const bool ok = std::isfinite(volume.extinction_scale) && volume.extinction_scale >= 0.0f &&
                  glm::all(glm::greaterThanEqual(volume.albedo, glm::vec3(0.0f))) &&
                  glm::all(glm::lessThanEqual(volume.albedo, glm::vec3(1.0f)));
  if (!ok)
    throw std::invalid_argument("VolumePass: " + label(volume, index) +
                                " needs a finite extinction scale >= 0 and an albedo in [0, 1]");
}

float smallest_voxel_edge(const scene::Volume& volume) {
  const glm::mat3 linear(volume.world_from_index);
  return std::min({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
}

GpuVolume to_gpu(const scene::Volume& volume, uint64_t grid_byte_offset, uint64_t majorant_offset) {
  GpuVolume gpu{};
  gpu.index_from_world = volume.index_from_world;
  // The trilinear support reaches one voxel beyond the active voxels (as in scene::optical_depth).
  gpu.support_min = glm::vec3(volume.active_index_min - 1);
  gpu.support_max = glm::vec3(volume.active_index_max + 1);
  gpu.step_length = VolumePass::kStepInVoxels * smallest_voxel_edge(volume);
  gpu.extinction_scale = volume.extinction_scale;
  gpu.albedo = volume.albedo;
  gpu.grid_byte_offset = uint32_t(grid_byte_offset);
  gpu.majorant_origin = volume.majorant.index_origin;
  gpu.brick_size = volume.majorant.brick_size;
  gpu.majorant_dims = volume.majorant.dims;
  gpu.majorant_offset = uint32_t(majorant_offset);
  gpu.voxel_size = smallest_voxel_edge(volume);
  gpu.octaves = uint32_t(std::clamp(volume.multiple_scattering.octaves, 1, 8));
  gpu.octave_attenuation = volume.multiple_scattering.attenuation;
  gpu.octave_contribution = volume.multiple_scattering.contribution;
  gpu.sky_light = volume.sky_light;
  gpu.sky_offset = shared::kNoSkyLighting;  // set with the grids
  return gpu;  // the atlas fields are set by VolumeDensityAtlas::build
}

gpu::Buffer storage_buffer(const gpu::Context& ctx, const void* data, size_t bytes, const char* name,
                           const std::string& sized_by = {}) {
  return gpu::create_buffer_with_data(
      ctx, {0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::DeviceLocal, name, sized_by}, data, bytes);
}

// What sizes the grid buffer, for a message when it does not fit the device: each grid's bytes.
std::string grid_sizes(const std::vector<scene::Volume>& volumes) {
  std::string sizes = "the scene's volumes: fewer, or smaller NanoVDB grids (";
  for (size_t i = 0; i < volumes.size(); ++i)
    sizes += (i ? ", " : "") + label(volumes[i], i) + " " + gpu::format_mib(volumes[i].nanovdb.size());
  return sizes + ")";
}

}  // namespace

VolumePass::VolumePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_march.comp"), "volume march")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("volume depth")) {}

void VolumePass::set_volumes(const std::vector<scene::Volume>& volumes) {
  std::vector<std::byte> grids;
  // Every volume's majorants one after another (the atlas's brick slots are indexed as
  // they are), then every volume's sky lighting (scene/volume_scattering.h).
  std::vector<float> brick_grids;
  std::vector<std::vector<float>> sky_grids;
  std::vector<GpuVolume> parameters;
  for (size_t i = 0; i < volumes.size(); ++i) {
    const scene::Volume& volume = volumes[i];
    check_grid(volume, i);
    check_majorant(volume, i);
    check_optics(volume, i);
    const size_t grid_offset = (grids.size() + kGridAlignment - 1) / kGridAlignment * kGridAlignment;
    if (grid_offset + volume.nanovdb.size() > kMaxGridBytes)
      throw std::invalid_argument("VolumePass: " + label(volume, i) +
                                  " does not fit: all NanoVDB grids together must stay under 4 GiB");
    grids.resize(grid_offset + volume.nanovdb.size());
    std::memcpy(grids.data() + grid_offset, volume.nanovdb.data(), volume.nanovdb.size());
    parameters.push_back(to_gpu(volume, grid_offset, brick_grids.size()));
    brick_grids.insert(brick_grids.end(), volume.majorant.max_density.begin(), volume.majorant.max_density.end());
    // The sky's light and the octaves' escape chance read it.
    const bool needs_sky = volume.sky_light > 0.0f || volume.multiple_scattering.octaves > 1;
    sky_grids.push_back(needs_sky ? scene::sky_lighting(volume) : std::vector<float>{});
  }
  for (size_t i = 0; i < volumes.size(); ++i) {
    if (sky_grids[i].empty()) continue;
    parameters[i].sky_offset = uint32_t(brick_grids.size());
    brick_grids.insert(brick_grids.end(), sky_grids[i].begin(), sky_grids[i].end());
  }
  // First, so that grids the device cannot hold (its storage buffer range: the march binds
  // them whole) are refused before the atlas is built and while the last volumes stay.
  gpu::Buffer grid_buffer;
  if (!volumes.empty())
    grid_buffer = storage_buffer(ctx_, grids.data(), grids.size(), "volume nanovdb grids", grid_sizes(volumes));

  volume_count_ = 0;
  grids_ = gpu::Buffer();
  brick_grids_ = gpu::Buffer();
  parameters_ = gpu::Buffer();
  boxes_.clear();
  atlas_.clear();
  atlas_.build(ctx_, volumes, parameters);
  if (!placeholder_) placeholder_ = gpu::create_buffer_from(ctx_, std::vector<GpuVolume>(1), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "no volumes");
  if (volumes.empty()) return;
  for (const scene::Volume& volume : volumes)
    boxes_.push_back({volume.world_from_index, glm::vec3(volume.active_index_min - 1), glm::vec3(volume.active_index_max + 1),
                      smallest_voxel_edge(volume), volume.majorant.brick_size, volume.world_bounds,
                      volume.lighting_cache_downsample, volume.lighting_cache});
  grids_ = std::move(grid_buffer);
  brick_grids_ = storage_buffer(ctx_, brick_grids.data(), brick_grids.size() * sizeof(float), "volume brick grids");
  parameters_ = storage_buffer(ctx_, parameters.data(), parameters.size() * sizeof(GpuVolume), "volume parameters");
  volume_count_ = uint32_t(volumes.size());
}

void bind_volumes(gpu::Bindings& bindings, const VolumeCasters& volumes, bool with_atlas) {
  bindings.buffer("VolumeNanoVdb", volumes.grids)
      .buffer("VolumeBrickGrids", volumes.majorants)
      .buffer("VolumeParameters", volumes.parameters);
  if (with_atlas)
    bindings.image("density_atlas", volumes.atlas, VolumeDensityAtlas::kLayout, volumes.atlas_sampler)
        .buffer("VolumeBrickSlots", volumes.brick_slots);
}

VolumeCasters VolumePass::casters() const {
  const VkBuffer none = placeholder_.handle();
  if (volume_count_ == 0) return {none, none, none, 0, 0, atlas_.view(), atlas_.sampler(), atlas_.slots().handle()};
  return {grids_.handle(), brick_grids_.handle(), parameters_.handle(), parameters_.size(), volume_count_,
          atlas_.view(),   atlas_.sampler(),    atlas_.slots().handle()};
}

rg::TextureHandle VolumePass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                           FrameInputs& frame) {
  const View& view = frame.view;
  const gpu::Buffer& lights = *frame.lights;
  const uint32_t light_count = frame.light_count;
  const ShadowInputs shadows = frame.shadows;
  if (volume_count_ == 0) return color;
  check_targets(graph, color, depth);
  const VkDeviceSize light_bytes = VkDeviceSize(std::max(light_count, 1u)) * sizeof(GpuLight);
  if (!lights || lights.size() < light_bytes)
    throw std::invalid_argument("VolumePass: the light buffer holds " + std::to_string(lights ? lights.size() : 0) +
                                " bytes; " + std::to_string(light_count) + " lights need " +
                                std::to_string(light_bytes));
  struct Targets {
    rg::TextureHandle color, depth;
    rg::BufferHandle page_requests;
  };
  const Targets& targets = graph.add_pass<Targets>("volumes", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.depth = b.read(depth, rg::Usage::Sampled);
        d.color = b.read_write(color, rg::Usage::StorageReadWrite);
        shadows.declare_reads(b);
        frame.fog.declare_reads(b);
        d.page_requests = frame.ask_for_pages(b);
      },
      [this, view, &lights, light_count, shadows, fog = frame.fog, skipping = majorant_skipping_](const Targets& d,
                                                                                 rg::PassContext& c) {
        record(c, d.color, d.depth, view, lights, light_count, shadows, fog, d.page_requests, skipping);
      });
  return targets.color;
}

// The shader writes rgba16f and reads one depth texel per colour pixel.
void VolumePass::check_targets(const rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth) {
  if (!color.valid() || !depth.valid() || color.graph_id != graph.id() || depth.graph_id != graph.id())
    throw std::invalid_argument("VolumePass: color and depth must be valid handles of this graph");
  const rg::TextureDesc& c = graph.resources().at(color.index).texture;
  const rg::TextureDesc& d = graph.resources().at(depth.index).texture;
  if (c.format != kColorFormat)
    throw std::invalid_argument("VolumePass: color must be R16G16B16A16_SFLOAT (VkFormat " +
                                std::to_string(int(kColorFormat)) + "), got VkFormat " + std::to_string(int(c.format)));
  if (d.format != kDepthFormat)
    throw std::invalid_argument("VolumePass: depth must be D32_SFLOAT (VkFormat " + std::to_string(int(kDepthFormat)) +
                                "), got VkFormat " + std::to_string(int(d.format)));
  if (c.width != d.width || c.height != d.height)
    throw std::invalid_argument("VolumePass: depth is " + std::to_string(d.width) + "x" + std::to_string(d.height) +
                                " but color is " + std::to_string(c.width) + "x" + std::to_string(c.height));
}

void VolumePass::record(rg::PassContext& c, rg::TextureHandle color, rg::TextureHandle depth, const View& view,
                        const gpu::Buffer& lights, uint32_t light_count, const ShadowInputs& shadows,
                        const FogInputs& fog, rg::BufferHandle page_requests, bool majorant_skipping) const {
  const rg::TextureDesc& size = c.desc(color);
  pipeline_.bind(c.cmd());
  gpu::Bindings bindings(ctx_, pipeline_);
  bindings.image("color_image", c.view(color), c.layout(color))
      .image("depth_texture", c.view(depth), c.layout(depth), depth_sampler_.handle())
      .buffer("VolumeNanoVdb", grids_)
      .buffer("VolumeBrickGrids", brick_grids_)
      .buffer("VolumeParameters", parameters_)
      .buffer("Lights", lights);
  shadows.bind(bindings, c);
  shadows.bind_page_requests(bindings, c, page_requests);
  fog.bind(bindings, c);
  bindings.push(c.cmd());
  Push push{view.inverse_view_projection, view.camera_position, volume_count_, {size.width, size.height},
            light_count, majorant_skipping ? 0u : shared::kMarchNoMajorantSkipping};
  pipeline_.push_constants(c.cmd(), push);
  pipeline_.dispatch_threads(c.cmd(), size.width, size.height);
}

}  // namespace avsm::passes
