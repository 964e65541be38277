// A host renderer with its own frame loop and its own descriptor sets that embeds the
// engine's adaptive volumetric shadow maps through plain Vulkan values only.
//
// It uses none of the engine's frame graph, bindings or push descriptors: it creates its
// own instance and device (enabling what avsm::gpu::DeviceRequirements lists), its own
// buffers for its casters (the same ground, box and hair as host_embed, examples/common),
// its own storage image, descriptor pool, set layouts and compute pipeline, and records
// each frame into its own command buffer:
//   avsm::Shadows::record(cmd, frame)   the shadow work, with its own barriers;
//   vkUpdateDescriptorSets              the lookup's buffers into the host's set 1 at the
//                                       bindings the host chose (kLookupBindings);
//   its own dispatch, barriers and copy of the picture to a mapped buffer.
//
// Output: ground.png and the checks host_embed makes (examples/common/ground_scene.h),
// with host_embed's options (examples/common/host_run.h); --no-shadows binds the
// unshadowed lookup buffers instead of recording the shadows.
#include <avsm/shadows.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/context.h"

#include "host_run.h"

namespace {

using namespace host;  // examples/common: the scene, the checks, the host device and frame loop, the run
using avsm::shared::GroundPush;

// Where the shader has the lookup's buffers (shaders/ground_shading.comp's macros).
constexpr uint32_t kLookupSet = 1;
constexpr avsm::ShadowLookupBindings kLookupBindings{/*parameters=*/3, /*atlas=*/0, /*list_heads=*/5, /*list_nodes=*/1,
                                                     /*page_requests=*/2};

// ---------------------------------------------------------------------------------------
// The host's own memory: buffers in host-visible memory (filled and read through a
// mapped pointer) and one device image.

uint32_t memory_type(VkPhysicalDevice physical, uint32_t allowed, VkMemoryPropertyFlags wanted) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((allowed & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  throw std::runtime_error("no memory type with properties " + std::to_string(wanted));
}

VkDeviceMemory allocate(const HostDevice& host, const VkMemoryRequirements& needs, VkMemoryPropertyFlags wanted) {
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = needs.size;
  info.memoryTypeIndex = memory_type(host.physical_device(), needs.memoryTypeBits, wanted);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check_vk(vkAllocateMemory(host.device(), &info, nullptr, &memory), "vkAllocateMemory");
  return memory;
}

class MappedBuffer {
 public:
  MappedBuffer(const HostDevice& host, VkDeviceSize size, VkBufferUsageFlags usage) : device_(host.device()), size_(size) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    check_vk(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device_, buffer_, &needs);
    memory_ = allocate(host, needs, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check_vk(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
    check_vk(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  }
  template <class T>
  MappedBuffer(const HostDevice& host, const std::vector<T>& contents, VkBufferUsageFlags usage)
      : MappedBuffer(host, contents.size() * sizeof(T), usage) {
    std::memcpy(mapped_, contents.data(), size_);  // coherent: visible to the next submission
  }
  ~MappedBuffer() {
    vkDestroyBuffer(device_, buffer_, nullptr);
    vkFreeMemory(device_, memory_, nullptr);
  }
  MappedBuffer(const MappedBuffer&) = delete;
  MappedBuffer& operator=(const MappedBuffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  const void* data() const { return mapped_; }

 private:
  VkDevice device_;
  VkDeviceSize size_;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  void* mapped_ = nullptr;
};

// The casters in the layouts the caster views document, as plain buffers.
struct HostCasters {
  explicit HostCasters(const HostDevice& host, const CasterArrays& arrays = make_casters())
      : bounds(arrays.bounds),
        vertices(host, arrays.vertices, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
        indices(host, arrays.indices, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT),
        strand_points(host, arrays.strand_points, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
        strand_segments(host, arrays.strand_segments, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
        strands(host, arrays.strands, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) {
    views.meshes.draws = arrays.draws;
    views.meshes.vertices = vertices.handle();
    views.meshes.vertices_size = vertices.size();
    views.meshes.indices = indices.handle();
    views.meshes.indices_size = indices.size();
    views.strands.segment_count = uint32_t(arrays.strand_segments.size());
    views.strands.points = strand_points.handle();
    views.strands.points_size = strand_points.size();
    views.strands.segments = strand_segments.handle();
    views.strands.segments_size = strand_segments.size();
    views.strands.strands = strands.handle();
    views.strands.strands_size = strands.size();
  }
  avsm::Bounds bounds;
  MappedBuffer vertices, indices, strand_points, strand_segments, strands;
  avsm::ShadowCasters views;
};

// ---------------------------------------------------------------------------------------
// The host's shading pass: its pipeline, set layouts, descriptor pool and sets, image.

class GroundShading {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

  GroundShading(const HostDevice& host, const avsm::Shadows& shadows, uint32_t size)
      : device_(host.device()), size_(size), readback_(host, VkDeviceSize(size) * size * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT) {
    create_image(host);
    create_layouts();
    create_pipeline(shadows.compile_glsl(HOST_SHADER_DIR "/ground_shading.comp"));
    create_sets();
  }
  ~GroundShading() {
    vkDestroyPipeline(device_, pipeline_, nullptr);
    vkDestroyPipelineLayout(device_, pipeline_layout_, nullptr);
    vkDestroyDescriptorPool(device_, pool_, nullptr);
    for (VkDescriptorSetLayout layout : set_layouts_) vkDestroyDescriptorSetLayout(device_, layout, nullptr);
    vkDestroyImageView(device_, view_, nullptr);
    vkDestroyImage(device_, image_, nullptr);
    vkFreeMemory(device_, image_memory_, nullptr);
  }
  GroundShading(const GroundShading&) = delete;
  GroundShading& operator=(const GroundShading&) = delete;

  // Writes the lookup's buffers into set 1 (before the set is bound: the frame's buffers
  // can change from one frame to the next), then shades the ground and copies the
  // picture to the mapped read-back buffer.
  void record(VkCommandBuffer cmd, const avsm::ShadowLookupBuffers& lookup) {
    const auto writes = lookup.writes(sets_[kLookupSet], kLookupBindings);
    vkUpdateDescriptorSets(device_, uint32_t(writes.size()), writes.data(), 0, nullptr);

    // The previous frame's copy read the image; its contents are not kept.
    image_barrier(cmd, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                  VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout_, 0, uint32_t(sets_.size()),
                            sets_.data(), 0, nullptr);
    const GroundPush push = ground_push();
    vkCmdPushConstants(cmd, pipeline_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (size_ + 7) / 8, (size_ + 7) / 8, 1);

    image_barrier(cmd, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {size_, size_, 1};
    vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1, &copy);
    // The picture, and the page requests the shading wrote (finish_frame() reads them).
    VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    to_host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    to_host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &to_host;
    vkCmdPipelineBarrier2(cmd, &dependency);
  }

  // After the frame completed.
  avsm::gpu::ImageRGBA32F picture() const {
    avsm::gpu::ImageRGBA32F image{size_, size_, std::vector<float>(size_t(size_) * size_ * 4)};
    std::memcpy(image.pixels.data(), readback_.data(), image.pixels.size() * sizeof(float));
    return image;
  }

 private:
  void create_image(const HostDevice& host) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = kFormat;
    info.extent = {size_, size_, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    check_vk(vkCreateImage(device_, &info, nullptr, &image_), "vkCreateImage");
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(device_, image_, &needs);
    image_memory_ = allocate(host, needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check_vk(vkBindImageMemory(device_, image_, image_memory_, 0), "vkBindImageMemory");
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image_;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = kFormat;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    check_vk(vkCreateImageView(device_, &view, nullptr, &view_), "vkCreateImageView");
  }

  // Set 0: the picture. Set 1: the shadow lookup, as the engine describes it.
  void create_layouts() {
    const VkDescriptorSetLayoutBinding image{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    const auto lookup = avsm::shadow_lookup_layout(kLookupBindings, VK_SHADER_STAGE_COMPUTE_BIT);
    for (const auto& [bindings, count] : {std::pair{&image, 1u}, std::pair{lookup.data(), uint32_t(lookup.size())}}) {
      VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
      info.bindingCount = count;
      info.pBindings = bindings;
      check_vk(vkCreateDescriptorSetLayout(device_, &info, nullptr, &set_layouts_.emplace_back()),
               "vkCreateDescriptorSetLayout");
    }
    const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GroundPush)};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = uint32_t(set_layouts_.size());
    info.pSetLayouts = set_layouts_.data();
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &push;
    check_vk(vkCreatePipelineLayout(device_, &info, nullptr, &pipeline_layout_), "vkCreatePipelineLayout");
  }

  void create_pipeline(const std::vector<uint32_t>& spirv) {
    VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    module_info.codeSize = spirv.size() * sizeof(uint32_t);
    module_info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check_vk(vkCreateShaderModule(device_, &module_info, nullptr, &module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = pipeline_layout_;
    const VkResult result = vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
    vkDestroyShaderModule(device_, module, nullptr);
    check_vk(result, "vkCreateComputePipelines");
  }

  void create_sets() {
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4}};
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = 2;
    pool.poolSizeCount = 2;
    pool.pPoolSizes = sizes;
    check_vk(vkCreateDescriptorPool(device_, &pool, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    info.descriptorPool = pool_;
    info.descriptorSetCount = uint32_t(set_layouts_.size());
    info.pSetLayouts = set_layouts_.data();
    sets_.resize(set_layouts_.size());
    check_vk(vkAllocateDescriptorSets(device_, &info, sets_.data()), "vkAllocateDescriptorSets");
    const VkDescriptorImageInfo image{VK_NULL_HANDLE, view_, VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = sets_[0];
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    write.pImageInfo = &image;
    vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
  }

  void image_barrier(VkCommandBuffer cmd, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 src_stage,
                     VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) const {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = src_stage;
    barrier.srcAccessMask = src_access;
    barrier.dstStageMask = dst_stage;
    barrier.dstAccessMask = dst_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image_;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
  }

  VkDevice device_;
  uint32_t size_;
  MappedBuffer readback_;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory image_memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSetLayout> set_layouts_;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

int run(const Options& options) {
  HostDevice host(options.validation);
  int failures = 0;
  {
    // The engine works on the host's device: it is lent, not created.
    avsm::gpu::Context context(host.lend());
    avsm::Shadows shadows(context, avsm::ShaderLocation::of_package());
    print_setup(context, shadows);

    const HostCasters casters(host);
    shadows.set_light(make_light(options), casters.bounds);
    GroundShading ground(host, shadows, options.size);
    // One frame at a time: the ground's descriptor set is written each frame, so a second
    // frame in flight would need a set of its own.
    HostFrames frames(host, 1);

    avsm::ShadowFrame frame;
    frame.camera = make_camera(options);
    frame.casters = casters.views;  // written through mapped memory before the submission: already visible
    frame.lookup_read_stages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;  // only the ground shading reads the shadows
    // Two frames: the second reuses what the first set up (the plan, the transients). A
    // paged map builds in its second frame the pages its first frame's shading asked
    // for; a third shows that nothing more is asked for.
    const int frame_count = options.paged ? 3 : 2;
    const auto finished = [&](const HostFrames::Slot& slot) { print_stats(slot.frame, shadows.finish_frame(slot.index)); };
    for (int n = 0; n < frame_count; ++n) {
      HostFrames::Slot& slot = frames.acquire(n, finished);
      frame.frame_slot = slot.index;
      frames.submit(slot, [&](VkCommandBuffer cmd) {
        ground.record(cmd, options.shadows ? shadows.record(cmd, frame) : avsm::lookup_buffers(shadows.unshadowed_lookup()));
      });
    }
    frames.finish_all(frame_count, finished);
    failures += report_picture(ground.picture(), options, context);
  }
  return failures + report_validation(host, options);
}

}  // namespace

int main(int argc, char** argv) { return host::host_main("host_raw", argc, argv, run); }
