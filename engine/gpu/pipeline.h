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
#include <mutex>
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
// request for one the context's PipelineCache holds returns it without compiling
// again. Every renderer on a context therefore compiles only what no earlier one did
// (on lavapipe compiling is most of a small frame's time), and hot reload, rebuilding
// every pass, creates only the edited shaders' pipelines anew.
class Pipeline {
 public:
  Pipeline() = default;
  static Pipeline compute(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name);
  static Pipeline graphics(const Context& ctx, const GraphicsPipelineDesc& desc);
  // How many pipelines the process compiled (not counting those from a cache), for tests.
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
  // The cached pipeline made from `key`, else create()'s, cached under `key`.
  static Pipeline shared(const Context& ctx, const std::string& key, const std::function<Pipeline()>& create);
  void create_layout(const Context& ctx, const std::vector<ShaderReflection>& stages);
  void push_constants(VkCommandBuffer cmd, const StructLayout& layout, const void* data) const;
  void release();
  friend class PipelineCache;
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

// The compiled pipelines of one Context (Context::pipelines()), by everything that went
// into them (kind, name, SPIR-V, fixed-function state). It keeps every pipeline in use
// and, of those no Pipeline uses any more, the `unused_limit` most recently asked for:
// a later renderer finds them compiled, while the pipelines of shaders that hot reload
// replaced, or of settings no longer rendered, are destroyed as newer ones are compiled
// (the limit is applied at each compile), so memory stays bounded however long a
// process reloads: at most the limit plus the pipelines in use at the last compile.
class PipelineCache {
 public:
  static constexpr size_t kDefaultUnusedLimit = 128;
  explicit PipelineCache(size_t unused_limit = kDefaultUnusedLimit) : unused_limit_(unused_limit) {}
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  // The pipeline cached under `key`, else `create`'s, which is then cached. Compiling
  // runs outside the lock: other threads may use the cache meanwhile.
  Pipeline find_or_create(const std::string& key, const std::function<Pipeline()>& create);
  // Lowers (or raises) how many unused pipelines are kept, destroying the oldest beyond it.
  void set_unused_limit(size_t limit);
  size_t size() const;         // pipelines held, in use or not
  size_t unused_count() const;  // of those, the ones no Pipeline uses

 private:
  struct Entry {
    Pipeline pipeline;   // owns a reference to the shared objects
    uint64_t last_asked = 0;
  };
  void trim_unused();  // with mutex_ held
  mutable std::mutex mutex_;
  std::map<std::string, Entry> entries_;
  size_t unused_limit_;
  uint64_t clock_ = 0;
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
