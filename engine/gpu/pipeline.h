#pragma once
// Compute and graphics pipelines whose layouts come from SPIR-V reflection.
// Descriptor set 0 is a push-descriptor set (VK_KHR_push_descriptor): a pass
// binds its resources by their shader names right before it draws or dispatches,
// with no pools or set lifetimes to manage. One 128-byte push-constant range
// covers all stages.
//
// At creation every struct the shaders share with C++ (shaders/shared/*.h) is
// checked against the SPIR-V layout, member by member, and every push-constant
// block must be such a struct: a mismatch is an InterfaceError naming the shader,
// the struct and the member.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/resources.h"
#include "gpu/spirv_reflect.h"
#include "gpu/struct_layout.h"

namespace avsm::gpu {

class Context;

// A shader and the C++ that drives it disagree on a shared struct or a binding.
class InterfaceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

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
  // `T` is the shared struct the shaders declare with GPU_PUSH_CONSTANTS.
  template <class T>
  void push_constants(VkCommandBuffer cmd, const T& value) const {
    static_assert(sizeof(T) <= 128, "push constants are limited to 128 bytes");
    push_constants(cmd, T::gpu_layout(), &value);
  }
  // Dispatches enough workgroups to cover `threads` invocations in each dimension.
  void dispatch_threads(VkCommandBuffer cmd, uint32_t x, uint32_t y = 1, uint32_t z = 1) const;

  // The binding the shaders declare under `name`; an InterfaceError when there is none.
  const DescriptorBinding& binding(std::string_view name) const;

  struct Objects;  // the Vulkan objects, shared between equal pipelines

 private:
  static Pipeline create_compute(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name);
  static Pipeline create_graphics(const Context& ctx, const GraphicsPipelineDesc& desc);
  // The live pipeline made from `key`, else create()'s, remembered under `key`.
  static Pipeline shared(const Context& ctx, const std::string& key, const std::function<Pipeline()>& create);
  void create_layout(const Context& ctx, const std::vector<ShaderReflection>& stages);
  void push_constants(VkCommandBuffer cmd, const StructLayout& layout, const void* data) const;
  void release();
  Pipeline copy_sharing() const;
  std::shared_ptr<Objects> objects_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  VkShaderStageFlags stages_ = 0;
  std::string push_block_;  // the push-constant struct's name; empty: none
  std::vector<DescriptorBinding> bindings_;
  std::array<uint32_t, 3> local_size_ = {1, 1, 1};
  std::string name_;
};

// Checks the shared structs of a pipeline's shaders against C++ (see above).
void check_shared_structs(const std::string& pipeline, const std::vector<ShaderReflection>& stages);

// One compute shader's pipelines per value of a build-time define (its variants, see
// ShaderLibrary::load), e.g. an AVSM build per node count. The SPIR-V is read when this
// is made; each pipeline is created the first time it is asked for, since compiling all
// of them up front costs start-up time for values no scene uses.
class ComputeVariants {
 public:
  ComputeVariants(const Context& ctx, std::map<uint32_t, std::vector<uint32_t>> spirv, std::string name)
      : ctx_(&ctx), spirv_(std::move(spirv)), name_(std::move(name)) {}
  // Throws std::invalid_argument for a value that has no variant.
  const Pipeline& get(uint32_t value) const;

 private:
  const Context* ctx_;
  std::map<uint32_t, std::vector<uint32_t>> spirv_;
  std::string name_;
  mutable std::map<uint32_t, Pipeline> pipelines_;
};

// Collects the resources of set 0 and pushes them. Resources are named as the
// shaders declare them (buffers by their block name, images and samplers by their
// variable name); type, element count and buffer size are checked against the
// reflection, so callers only say what to bind.
class Bindings {
 public:
  Bindings(const Context& ctx, const Pipeline& pipeline) : ctx_(ctx), pipeline_(pipeline) {}
  Bindings& buffer(std::string_view name, BufferRange buffer);
  // Sampled, storage or combined image; `sampler` only for combined image samplers.
  Bindings& image(std::string_view name, VkImageView view, VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE);
  Bindings& sampler(std::string_view name, VkSampler sampler);
  // Every element of an array binding (whole buffers; storage or sampled images).
  Bindings& buffer_array(std::string_view name, std::span<const BufferRange> buffers);
  Bindings& image_array(std::string_view name, std::span<const VkImageView> views,
                        std::span<const VkImageLayout> layouts);
  void push(VkCommandBuffer cmd);

 private:
  VkWriteDescriptorSet& add(const DescriptorBinding& binding, uint32_t count);
  void check_buffer(const DescriptorBinding& binding, const BufferRange& buffer) const;
  void check_image_type(const DescriptorBinding& binding, bool has_sampler) const;
  [[noreturn]] void fail(const DescriptorBinding& binding, const std::string& problem) const;
  const Context& ctx_;
  const Pipeline& pipeline_;
  std::vector<VkWriteDescriptorSet> writes_;
  std::vector<VkDescriptorBufferInfo> buffers_;  // reserved, so pointers stay valid
  std::vector<VkDescriptorImageInfo> images_;
};

}  // namespace avsm::gpu
