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
#include <utility>

#include "gpu/barriers.h"
#include "gpu/context.h"
#include "gpu/device_limits.h"
#include "gpu/transfer.h"
#include "passes/frame/lights.h"
#include "passes/shadows/shadow_maps.h"
#include "scene/volume_scattering.h"
#include "shared/passes/camera/volumes/volume_march.h"

namespace avsm::passes {
namespace {

using Push = shared::VolumeMarchPush;  // shaders/shared/passes/camera/volumes/volume_march.h

// The packing's sections in a staging buffer, where the upload copies them from.
struct StagingLayout {
  VkDeviceSize grids = 0, brick_grids = 0, parameters = 0, slots = 0, atlas = 0, end = 0;
};

StagingLayout staging_layout(const PackedVolumes& packed, const std::vector<std::shared_ptr<const PreparedVolume>>& parts) {
  const auto aligned = [](VkDeviceSize offset) { return (offset + 15) / 16 * 16; };
  StagingLayout layout;
  layout.brick_grids = aligned(packed.grids.size());
  layout.parameters = aligned(layout.brick_grids + packed.brick_grids.size() * sizeof(float));
  layout.slots = aligned(layout.parameters + packed.parameters.size() * sizeof(GpuVolume));
  layout.atlas = aligned(layout.slots + packed.slots.size() * sizeof(uint32_t));
  layout.end = layout.atlas;
  for (const auto& part : parts) layout.end += part->atlas.texels.size() * sizeof(uint16_t);
  return layout;
}

void write_staging(void* mapped, const StagingLayout& layout, const PackedVolumes& packed,
                   const std::vector<std::shared_ptr<const PreparedVolume>>& parts) {
  auto* bytes = static_cast<std::byte*>(mapped);
  std::memcpy(bytes + layout.grids, packed.grids.data(), packed.grids.size());
  std::memcpy(bytes + layout.brick_grids, packed.brick_grids.data(), packed.brick_grids.size() * sizeof(float));
  std::memcpy(bytes + layout.parameters, packed.parameters.data(), packed.parameters.size() * sizeof(GpuVolume));
  std::memcpy(bytes + layout.slots, packed.slots.data(), packed.slots.size() * sizeof(uint32_t));
  VkDeviceSize at = layout.atlas;
  for (const auto& part : parts) {
    std::memcpy(bytes + at, part->atlas.texels.data(), part->atlas.texels.size() * sizeof(uint16_t));
    at += part->atlas.texels.size() * sizeof(uint16_t);
  }
}

gpu::Buffer device_buffer(const gpu::Context& ctx, VkDeviceSize bytes, const char* name, const std::string& sized_by = {}) {
  return gpu::Buffer::create(ctx, {std::max<VkDeviceSize>(bytes, 16),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   gpu::MemoryLocation::DeviceLocal, name, sized_by});
}

// What sizes the grid buffer, for a message when it does not fit the device: each grid's bytes.
std::string grid_sizes(const std::vector<std::shared_ptr<const PreparedVolume>>& parts) {
  std::string sizes = "the scene's volumes: fewer, or smaller NanoVDB grids (";
  for (size_t i = 0; i < parts.size(); ++i)
    sizes += (i ? ", " : "") + volume_label(*parts[i]->volume, i) + " " + gpu::format_mib(parts[i]->volume->nanovdb.size());
  return sizes + ")";
}

}  // namespace

VolumePass::VolumePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_march.comp"), "volume march")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("volume depth")) {}

void VolumePass::set_volumes(const std::vector<scene::Volume>& volumes) {
  std::vector<std::shared_ptr<const PreparedVolume>> parts;
  for (size_t i = 0; i < volumes.size(); ++i)
    parts.push_back(std::make_shared<PreparedVolume>(
        prepare_volume(std::make_shared<scene::Volume>(volumes[i]), i, ctx_.info().max_image_dimension_3d)));
  set_prepared(std::move(parts));
}

void VolumePass::set_prepared(std::vector<std::shared_ptr<const PreparedVolume>> parts) {
  const PackedVolumes packed = pack_volumes(parts, ctx_.info().max_image_dimension_3d);
  allocate(packed, parts, /*headroom=*/1.0);
  upload_now(packed, parts);
  parts_ = std::move(parts);
  for (Upload& upload : pending_) upload = {};
}

void VolumePass::allocate(const PackedVolumes& packed, const std::vector<std::shared_ptr<const PreparedVolume>>& parts,
                          double headroom) {
  // The grids first, so that grids the device cannot hold (its storage buffer range: the
  // march binds them whole) are refused before anything else is replaced.
  const auto grown = [headroom](size_t bytes) { return VkDeviceSize(double(bytes) * headroom); };
  gpu::Buffer grids;
  if (!parts.empty()) grids = device_buffer(ctx_, grown(packed.grids.size()), "volume nanovdb grids", grid_sizes(parts));
  volume_count_ = 0;
  grids_ = std::move(grids);
  brick_grids_ = gpu::Buffer();
  parameters_ = gpu::Buffer();
  boxes_.clear();
  atlas_.clear();
  atlas_initialized_ = false;
  const glm::ivec3 limit(int(ctx_.info().max_image_dimension_3d));
  atlas_.create(ctx_, glm::min(glm::ivec3(glm::vec3(packed.atlas_size) * float(headroom)), limit),
                grown(packed.slots.size()));
  if (!placeholder_) placeholder_ = gpu::create_buffer_from(ctx_, std::vector<GpuVolume>(1), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "no volumes");
  if (parts.empty()) return;
  brick_grids_ = device_buffer(ctx_, grown(packed.brick_grids.size() * sizeof(float)), "volume brick grids");
  parameters_ = device_buffer(ctx_, packed.parameters.size() * sizeof(GpuVolume), "volume parameters");
}

bool VolumePass::fits(const PackedVolumes& packed) const {
  return grids_ && packed.grids.size() <= grids_.size() && packed.brick_grids.size() * sizeof(float) <= brick_grids_.size() &&
         packed.parameters.size() * sizeof(GpuVolume) <= parameters_.size() && atlas_.fits(packed);
}

void VolumePass::upload_now(const PackedVolumes& packed, const std::vector<std::shared_ptr<const PreparedVolume>>& parts) {
  gpu::Buffer staging;  // only streaming keeps staging memory
  const Upload upload = stage(packed, parts, staging);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { record_upload(cmd, upload); });
  describe(parts);
}

VolumePass::Upload VolumePass::stage(const PackedVolumes& packed, const std::vector<std::shared_ptr<const PreparedVolume>>& parts,
                                     gpu::Buffer& staging) {
  const StagingLayout layout = staging_layout(packed, parts);
  if (!staging || staging.size() < layout.end)
    staging = gpu::Buffer::create(ctx_, {std::max<VkDeviceSize>(layout.end + layout.end / 4, 256), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                         gpu::MemoryLocation::HostUpload, "volume staging"});
  write_staging(staging.mapped(), layout, packed, parts);
  Upload upload;
  upload.staging = staging.handle();
  upload.copies = {{grids_.handle(), {layout.grids, 0, packed.grids.size()}},
                   {brick_grids_.handle(), {layout.brick_grids, 0, packed.brick_grids.size() * sizeof(float)}},
                   {parameters_.handle(), {layout.parameters, 0, packed.parameters.size() * sizeof(GpuVolume)}},
                   {atlas_.slots().handle(), {layout.slots, 0, packed.slots.size() * sizeof(uint32_t)}}};
  upload.atlas = atlas_copies(parts, packed, layout.atlas);
  upload.parts = parts;
  return upload;
}

// Copies a staged packing into the volumes' buffers and atlas. These are scene data that
// passes bind outside the graph (VolumeCasters), so the copies carry their own barriers:
// after every earlier read (earlier frames on the one queue, or this frame's passes
// before), and before every later one.
void VolumePass::record_upload(VkCommandBuffer cmd, const Upload& upload) {
  std::vector<VkBufferMemoryBarrier2> before, after;
  for (const auto& [buffer, copy] : upload.copies) {
    if (buffer == VK_NULL_HANDLE) continue;
    before.push_back(gpu::make_buffer_barrier(buffer, gpu::kAllShaderRead, gpu::kTransferWrite));
    after.push_back(gpu::make_buffer_barrier(buffer, gpu::kTransferWrite, gpu::kAllShaderRead));
  }
  const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  const VkImageMemoryBarrier2 to_copy = gpu::make_image_barrier(
      atlas_.image().handle(), all, atlas_initialized_ ? VolumeDensityAtlas::kLayout : VK_IMAGE_LAYOUT_UNDEFINED,
      VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, gpu::kAllShaderRead, gpu::kTransferWrite);
  const VkImageMemoryBarrier2 to_read = gpu::make_image_barrier(atlas_.image().handle(), all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                                VolumeDensityAtlas::kLayout, gpu::kTransferWrite, gpu::kAllShaderRead);
  const auto barriers = [cmd](const std::vector<VkBufferMemoryBarrier2>& buffers, const VkImageMemoryBarrier2& image) {
    VkDependencyInfo info{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    info.bufferMemoryBarrierCount = uint32_t(buffers.size());
    info.pBufferMemoryBarriers = buffers.data();
    info.imageMemoryBarrierCount = 1;
    info.pImageMemoryBarriers = &image;
    vkCmdPipelineBarrier2(cmd, &info);
  };
  barriers(before, to_copy);
  for (const auto& [buffer, copy] : upload.copies)
    if (buffer != VK_NULL_HANDLE && copy.size > 0) vkCmdCopyBuffer(cmd, upload.staging, buffer, 1, &copy);
  if (!upload.atlas.empty())
    vkCmdCopyBufferToImage(cmd, upload.staging, atlas_.image().handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           uint32_t(upload.atlas.size()), upload.atlas.data());
  barriers(after, to_read);
  atlas_initialized_ = true;
}

void VolumePass::stream(std::vector<std::shared_ptr<const PreparedVolume>> parts, uint32_t slot) {
  if (slot >= pending_.size()) throw std::invalid_argument("VolumePass::stream: frame slot " + std::to_string(slot) + " of " + std::to_string(pending_.size()));
  if (parts.size() != parts_.size())
    throw std::invalid_argument("VolumePass::stream: " + std::to_string(parts.size()) + " volumes for a scene of " +
                                std::to_string(parts_.size()) + "; set_volumes() changes their number");
  const PackedVolumes packed = pack_volumes(parts, ctx_.info().max_image_dimension_3d);
  if (!fits(packed)) {
    // Larger than any frame before: new buffers, with room to grow into, once the frames
    // in flight that read the old ones are done (rare: a sequence grows a few times).
    vkDeviceWaitIdle(ctx_.device());
    allocate(packed, parts, /*headroom=*/1.5);
    upload_now(packed, parts);
    for (Upload& upload : pending_) upload = {};
    ++stream_stats_.reallocations;
  } else {
    pending_[slot] = stage(packed, parts, staging_[slot]);
  }
  ++stream_stats_.frames;
  parts_ = std::move(parts);
}

void VolumePass::add_upload(rg::Graph& graph, uint32_t slot) {
  if (slot >= pending_.size() || pending_[slot].staging == VK_NULL_HANDLE) return;
  Upload upload = std::exchange(pending_[slot], {});
  // The CPU-side description follows what the GPU holds from this frame on.
  describe(upload.parts);
  graph.add_pass("volume upload", rg::QueueType::Transfer, [](rg::PassBuilder& b) { b.side_effect(); },
                 [this, upload = std::move(upload)](rg::PassContext& c) { record_upload(c.cmd(), upload); });
}

void VolumePass::describe(const std::vector<std::shared_ptr<const PreparedVolume>>& parts) {
  boxes_.clear();
  for (const auto& part : parts) {
    const scene::Volume& volume = *part->volume;
    const GpuVolume& gpu = part->parameters;
    boxes_.push_back({volume.world_from_index, gpu.support_min, gpu.support_max, gpu.voxel_size, gpu.brick_size,
                      volume.world_bounds, volume.lighting_cache_downsample, volume.lighting_cache});
  }
  volume_count_ = uint32_t(parts.size());
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
  return {grids_.handle(), brick_grids_.handle(), parameters_.handle(), volume_count_ * sizeof(GpuVolume), volume_count_,
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
