#include "passes/camera/volumes/volume_lighting_cache_pass.h"

#include <glm/gtc/matrix_transform.hpp>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "passes/frame/lights.h"
#include "passes/shadows/shadow_maps.h"
#include "shared/passes/camera/volumes/volume_lighting_cache.h"

namespace avsm::passes {
namespace {

using Push = shared::VolumeLightingCachePush;  // shaders/shared/passes/camera/volumes/volume_lighting_cache.h

float distance_to_box(const glm::vec3& p, const scene::Bounds& box) {
  const glm::vec3 outside = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
  return glm::length(outside);
}

// Voxels per cell: the scene's downsample, coarser where a march pixel or the finest
// light texel covers more than that at the volume, never coarser than a brick.
float voxels_per_cell(const VolumeBox& box, const View& view, uint32_t divisor, float light_texel) {
  const float radians_per_pixel = 2.0f / (std::abs(view.projection[1][1]) * float(view.height));
  const float footprint = distance_to_box(view.camera_position, box.world_bounds) * radians_per_pixel * float(divisor);
  const float finest = std::max(footprint, light_texel);
  return std::clamp(std::max(box.cache_downsample, finest / box.voxel_size), 1.0f, float(box.brick_size));
}

GpuCacheLayout layout_for(const VolumeBox& box, float per_cell, int first_slice) {
  const glm::vec3 extent = box.support_max - box.support_min;
  GpuCacheLayout layout{};
  layout.first_slice = first_slice;
  if (!box.cached) return layout;  // no cells: dims 0 tells the march to look the maps up
  layout.dims = glm::max(glm::ivec3(glm::ceil(extent / per_cell)), glm::ivec3(1));
  layout.cells_per_voxel = glm::vec3(layout.dims) / extent;
  layout.cell_origin = box.support_min;
  layout.world_from_cell = box.world_from_index * glm::translate(glm::mat4(1.0f), box.support_min) *
                           glm::scale(glm::mat4(1.0f), extent / glm::vec3(layout.dims));
  return layout;
}

}  // namespace

std::vector<float> VolumeLightingCachePass::finest_light_texels(const std::vector<VolumeBox>& boxes,
                                                                const std::vector<LightView>& lights) {
  std::vector<float> texels;
  for (const VolumeBox& box : boxes) {
    const glm::vec3 centre = 0.5f * (box.world_bounds.min + box.world_bounds.max);
    float finest = 0.0f;
    for (const LightView& light : lights) {
      const float texel = light.texel_size(light.depth(centre));
      if (texel > 0.0f) finest = finest > 0.0f ? std::min(finest, texel) : texel;
    }
    texels.push_back(finest);
  }
  return texels;
}

std::vector<GpuCacheLayout> VolumeLightingCachePass::plan(const std::vector<VolumeBox>& boxes, const View& view,
                                                          uint32_t divisor, uint32_t max_texels,
                                                          const std::vector<float>& light_texels) {
  std::vector<float> per_cell;
  for (size_t i = 0; i < boxes.size(); ++i)
    per_cell.push_back(voxels_per_cell(boxes[i], view, divisor, i < light_texels.size() ? light_texels[i] : 0.0f));
  // Coarsen every volume together until the stack fits the device's 3D image size.
  for (int attempt = 0;; ++attempt) {
    std::vector<GpuCacheLayout> layouts;
    int slices = 0;
    bool fits = true;
    for (size_t i = 0; i < boxes.size(); ++i) {
      layouts.push_back(layout_for(boxes[i], per_cell[i], slices));
      slices += layouts.back().dims.z;
      fits = fits && uint32_t(glm::max(layouts.back().dims.x, layouts.back().dims.y)) <= max_texels;
    }
    if (fits && uint32_t(slices) <= max_texels) return layouts;
    bool coarsened = false;
    for (size_t i = 0; i < boxes.size(); ++i) {
      const float coarser = std::min(per_cell[i] * 1.25f, float(boxes[i].brick_size));
      coarsened = coarsened || coarser > per_cell[i];
      per_cell[i] = coarser;
    }
    if (!coarsened || attempt > 64)
      throw std::invalid_argument("VolumeLightingCachePass: the lighting caches of " + std::to_string(boxes.size()) +
                                  " volumes need " + std::to_string(slices) + " slices even with brick-sized cells, "
                                  "more than this device's 3D image limit of " + std::to_string(max_texels) +
                                  " (use fewer volumes or larger majorant_brick_size)");
  }
}

VolumeLightingCachePass::VolumeLightingCachePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_lighting_cache.comp"),
                                       "volume lighting cache")),
      sampler_(ctx, {VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false,
                     VK_COMPARE_OP_LESS_OR_EQUAL, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE, "volume lighting cache"}) {}

void VolumeLightingCachePass::add_to_graph(rg::Graph& graph, FrameInputs& inputs) {
  const View& view = inputs.view;
  const std::vector<LightView>& light_views = *inputs.light_views;
  const std::vector<VolumeBox>& boxes = inputs.volumes->boxes();
  std::vector<GpuCacheLayout> layouts = plan(boxes, view, uint32_t(inputs.shading.resolution_divisor),
                                             ctx_.info().max_image_dimension_3d, finest_light_texels(boxes, light_views));
  glm::uvec3 size(1, 1, 0);
  cell_count_ = 0;
  for (const GpuCacheLayout& l : layouts) {
    size = glm::uvec3(glm::max(size.x, uint32_t(l.dims.x)), glm::max(size.y, uint32_t(l.dims.y)), size.z + uint32_t(l.dims.z));
    cell_count_ += uint64_t(l.dims.x) * uint64_t(l.dims.y) * uint64_t(l.dims.z);
  }
  size.z = std::max(size.z, 1u);  // every volume's cache off: one unused slice
  const uint64_t layout_bytes = layouts.size() * sizeof(GpuCacheLayout);
  if (layout_bytes > 65536)
    throw std::invalid_argument("VolumeLightingCachePass: " + std::to_string(layouts.size()) +
                                " volumes exceed the " + std::to_string(65536 / sizeof(GpuCacheLayout)) +
                                " cache layouts one frame uploads");

  // The layouts change with the view, so they travel with the frame (vkCmdUpdateBuffer).
  struct Upload {
    rg::BufferHandle layouts;
  };
  const Upload& upload = graph.add_pass<Upload>("volume cache layout", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Upload& d) {
        d.layouts = b.write(b.create_buffer("volume cache layouts", {layout_bytes}), rg::Usage::TransferDst);
      },
      [layouts](const Upload& d, rg::PassContext& c) {
        vkCmdUpdateBuffer(c.cmd(), c.buffer(d.layouts), 0, layouts.size() * sizeof(GpuCacheLayout), layouts.data());
      });

  struct Cache {
    rg::BufferHandle layouts;
    rg::TextureHandle image;
    rg::BufferHandle page_requests;
  };
  const Cache& cache = graph.add_pass<Cache>("volume lighting cache", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Cache& d) {
        d.layouts = b.read(upload.layouts, rg::Usage::StorageRead);
        d.image = b.write(b.create_texture("volume lighting cache", {size.x, size.y, size.z, 1, 1, kFormat,
                                                            "the cache's cells: a volume's lighting_cache.downsample "
                                                            "higher, or --volume-resolution-divisor"}),
                          rg::Usage::StorageWrite);
        inputs.shadows.declare_reads(b);
        d.page_requests = inputs.ask_for_pages(b);
      },
      [this, inputs, size, camera = view.camera_position](const Cache& d, rg::PassContext& c) {
        const VolumeCasters volumes = inputs.volumes->casters();
        pipeline_.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline_);
        b.image("cache_image", c.view(d.image), c.layout(d.image));
        bind_volumes(b, volumes, /*with_atlas=*/false);
        b.buffer("CacheLayouts", c.buffer(d.layouts)).buffer("Lights", *inputs.lights);
        inputs.shadows.bind(b, c);
        inputs.shadows.bind_page_requests(b, c, d.page_requests);
        b.push(c.cmd());
        pipeline_.push_constants(c.cmd(), Push{camera, volumes.volume_count, size, inputs.light_count});
        pipeline_.dispatch_threads(c.cmd(), size.x, size.y, size.z);
      });
  inputs.cache = VolumeLightingCache{cache.image, cache.layouts, sampler_.handle()};
}

}  // namespace avsm::passes
