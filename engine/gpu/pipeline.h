#pragma once
// Compute and graphics pipelines whose layouts come from SPIR-V reflection.
// Descriptor set 0 is a push-descriptor set (VK_KHR_push_descriptor): a pass
// binds its resources right before it draws or dispatches, with no pools or
// set lifetimes to manage. One 128-byte push-constant range covers all stages.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/spirv_reflect.h"

namespace avsm::gpu {

class Context;

enum class BlendMode { None, Alpha, PremultipliedAlpha, Additive };

struct GraphicsPipelineDesc {
  std::string name;
  std::vector<uint32_t> vertex;
  std::vector<uint32_t> geometry;  // optional
  std::vector<uint32_t> fragment;  // optional (depth-only passes)
  std::vector<VkFormat> color_formats;
  VkFormat depth_format = VK_FORMAT_UNDEFINED;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cull_mode = VK_CULL_MODE_NONE;
  VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depth_test = false;
  bool depth_write = false;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
  BlendMode blend = BlendMode::None;
};

// Pipelines built from the same SPIR-V and state share their Vulkan objects: a
// second request for one that is alive returns it without compiling again. Hot
// reload relies on this, rebuilding every pass while only the edited shaders'
// pipelines are created anew. The objects go when the last Pipeline using them does.
class Pipeline {
 public:
  Pipeline() = default;
  static Pipeline compute(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name);
  static Pipeline graphics(const Context& ctx, const GraphicsPipelineDesc& desc);
  // How many pipelines the process created (not counting shared ones), for tests.
  static uint64_t created_count();
  ~Pipeline();
  Pipeline(Pipeline&& other) noexcept;
  Pipeline& operator=(Pipeline&& other) noexcept;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bind_point() const { return bind_point_; }
  const std::string& name() const { return name_; }
  const std::vector<DescriptorBinding>& bindings() const { return bindings_; }
  const std::array<uint32_t, 3>& local_size() const { return local_size_; }
  explicit operator bool() const { return pipeline_ != VK_NULL_HANDLE; }

  void bind(VkCommandBuffer cmd) const;
  void push_constants(VkCommandBuffer cmd, const void* data, uint32_t bytes) const;
  template <class T>
  void push_constants(VkCommandBuffer cmd, const T& value) const {
    static_assert(sizeof(T) <= 128, "push constants are limited to 128 bytes");
    push_constants(cmd, &value, sizeof(T));
  }
  // Dispatches enough workgroups to cover `threads` invocations in each dimension.
  void dispatch_threads(VkCommandBuffer cmd, uint32_t x, uint32_t y = 1, uint32_t z = 1) const;

  const DescriptorBinding& binding(uint32_t index) const;

  struct Objects;  // the Vulkan objects, shared between equal pipelines

 private:
  static Pipeline create_compute(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name);
  static Pipeline create_graphics(const Context& ctx, const GraphicsPipelineDesc& desc);
  // The live pipeline made from `key`, else create()'s, remembered under `key`.
  static Pipeline shared(const Context& ctx, const std::string& key, const std::function<Pipeline()>& create);
  void create_layout(const Context& ctx, const std::vector<ShaderReflection>& stages);
  void release();
  Pipeline copy_sharing() const;
  std::shared_ptr<Objects> objects_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  VkShaderStageFlags stages_ = 0;
  bool has_push_constants_ = false;
  std::vector<DescriptorBinding> bindings_;
  std::array<uint32_t, 3> local_size_ = {1, 1, 1};
  std::string name_;
};

// Collects the resources of set 0 and pushes them. The descriptor type of each
// binding comes from the pipeline's reflection, so callers only say what to bind.
class Bindings {
 public:
  Bindings(const Context& ctx, const Pipeline& pipeline) : ctx_(ctx), pipeline_(pipeline) {}
  Bindings& buffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
  // Sampled, storage or combined image; `sampler` only for combined image samplers.
  Bindings& image(uint32_t binding, VkImageView view, VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE);
  Bindings& sampler(uint32_t binding, VkSampler sampler);
  // Every element of an array binding (whole buffers; storage or sampled images).
  Bindings& buffer_array(uint32_t binding, std::span<const VkBuffer> buffers);
  Bindings& image_array(uint32_t binding, std::span<const VkImageView> views, std::span<const VkImageLayout> layouts);
  void push(VkCommandBuffer cmd);

 private:
  VkWriteDescriptorSet& add(uint32_t binding, uint32_t count);
  void check_buffer_type(uint32_t binding, VkDescriptorType type) const;
  void check_image_type(uint32_t binding, VkDescriptorType type, bool has_sampler) const;
  const Context& ctx_;
  const Pipeline& pipeline_;
  std::vector<VkWriteDescriptorSet> writes_;
  std::vector<VkDescriptorBufferInfo> buffers_;  // reserved, so pointers stay valid
  std::vector<VkDescriptorImageInfo> images_;
};

}  // namespace avsm::gpu
