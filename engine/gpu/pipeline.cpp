#include "gpu/pipeline.h"

#include <algorithm>

#include <atomic>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "gpu/context.h"
#include "gpu/vk_check.h"

namespace avsm::gpu {

static constexpr uint32_t kPushConstantBytes = 128;
static constexpr size_t kMaxBindingsPerPush = 32;
static constexpr size_t kMaxInfosPerPush = 64;

static VkShaderModule create_module(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
  ctx.set_name(module, VK_OBJECT_TYPE_SHADER_MODULE, name);
  return module;
}

// Owns what a Pipeline's handles point at; destroyed with the last Pipeline sharing it.
struct Pipeline::Objects {
  const Context* ctx = nullptr;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  ~Objects() {  // names first: Context::forget_name says why
    if (pipeline) ctx->destroy_named(pipeline, VK_OBJECT_TYPE_PIPELINE, vkDestroyPipeline);
    if (layout) ctx->destroy_named(layout, VK_OBJECT_TYPE_PIPELINE_LAYOUT, vkDestroyPipelineLayout);
    if (set_layout) ctx->destroy_named(set_layout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, vkDestroyDescriptorSetLayout);
  }
};

namespace {

std::atomic<uint64_t> pipelines_created{0};

void append_bytes(std::string& key, const void* data, size_t bytes) {
  key.append(reinterpret_cast<const char*>(&bytes), sizeof(bytes));
  key.append(static_cast<const char*>(data), bytes);
}
void append_words(std::string& key, std::span<const uint32_t> words) {
  append_bytes(key, words.data(), words.size_bytes());
}
template <class T>
void append_value(std::string& key, const T& value) {
  append_bytes(key, &value, sizeof(value));
}

}  // namespace

uint64_t Pipeline::created_count() { return pipelines_created.load(); }

Pipeline Pipeline::copy_sharing() const {
  Pipeline p;
  p.objects_ = objects_;
  p.pipeline_ = pipeline_;
  p.layout_ = layout_;
  p.set_layout_ = set_layout_;
  p.bind_point_ = bind_point_;
  p.stages_ = stages_;
  p.push_block_ = push_block_;
  p.bindings_ = bindings_;
  p.local_size_ = local_size_;
  p.name_ = name_;
  return p;
}

Pipeline Pipeline::shared(const Context& ctx, const std::string& key, const std::function<Pipeline()>& create) {
  return ctx.pipelines().find_or_create(key, [&] {
    ++pipelines_created;
    return create();
  });
}

// ---------------------------------------------------------------- PipelineCache
//
// No VkPipelineCache: lavapipe (Mesa 22.3) keeps nothing in one (vkGetPipelineCacheData
// returns its 32-byte header alone after pipelines were created with it). Across
// processes Mesa's own shader disk cache (~/.cache/mesa_shader_cache, on by default)
// already keeps llvmpipe's compiled code: a small capture of the default scene took
// 19.9 CPU seconds with an empty MESA_SHADER_CACHE_DIR, 8.7 with it filled.

Pipeline PipelineCache::find_or_create(const std::string& key, const std::function<Pipeline()>& create) {
  std::unique_lock lock(mutex_);
  auto found = entries_.find(key);
  if (found != entries_.end()) {
    found->second.last_asked = ++clock_;
    return found->second.pipeline.copy_sharing();
  }
  lock.unlock();
  Pipeline created = create();
  lock.lock();
  // Another thread may have compiled the same meanwhile: the first one cached wins.
  auto [entry, inserted] = entries_.try_emplace(key);
  if (inserted) entry->second.pipeline = created.copy_sharing();
  entry->second.last_asked = ++clock_;
  trim_unused();
  return entry->second.pipeline.copy_sharing();
}

void PipelineCache::set_unused_limit(size_t limit) {
  std::lock_guard lock(mutex_);
  unused_limit_ = limit;
  trim_unused();
}

size_t PipelineCache::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

// Only the cache holds an unused pipeline's objects. Nobody can take a new reference
// without the lock, so one counted unused here stays so until it is destroyed.
size_t PipelineCache::unused_count() const {
  std::lock_guard lock(mutex_);
  return size_t(std::count_if(entries_.begin(), entries_.end(),
                              [](const auto& e) { return e.second.pipeline.objects_.use_count() == 1; }));
}

void PipelineCache::trim_unused() {
  std::vector<std::map<std::string, Entry>::iterator> unused;
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->second.pipeline.objects_.use_count() == 1) unused.push_back(it);
  if (unused.size() <= unused_limit_) return;
  // Oldest first. Without the cache a pipeline went with its last Pipeline; the cache
  // only defers that, so no command buffer in flight can still use an unused one.
  std::sort(unused.begin(), unused.end(),
            [](const auto& a, const auto& b) { return a->second.last_asked < b->second.last_asked; });
  for (size_t i = 0; i < unused.size() - unused_limit_; ++i) entries_.erase(unused[i]);
}

Pipeline Pipeline::compute(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name) {
  std::string key = "compute";
  append_bytes(key, name.data(), name.size());
  append_words(key, spirv);
  return shared(ctx, key, [&] { return create_compute(ctx, spirv, name); });
}

Pipeline Pipeline::graphics(const Context& ctx, const GraphicsPipelineDesc& desc) {
  std::string key = "graphics";
  append_bytes(key, desc.name.data(), desc.name.size());
  append_words(key, desc.vertex);
  append_words(key, desc.geometry);
  append_words(key, desc.fragment);
  append_bytes(key, desc.color_formats.data(), desc.color_formats.size() * sizeof(VkFormat));
  append_value(key, desc.depth_format);
  append_value(key, desc.topology);
  append_value(key, desc.cull_mode);
  append_value(key, desc.front_face);
  append_value(key, desc.depth_test);
  append_value(key, desc.depth_write);
  append_value(key, desc.depth_compare);
  append_value(key, desc.blend);
  return shared(ctx, key, [&] { return create_graphics(ctx, desc); });
}

void Pipeline::create_layout(const Context& ctx, const std::vector<ShaderReflection>& stages) {
  objects_ = std::make_shared<Objects>();
  objects_->ctx = &ctx;
  // Merge bindings across stages; the same binding must mean the same thing everywhere.
  check_shared_structs(name_, stages);
  for (const ShaderReflection& stage : stages) {
    stages_ |= stage.stage;
    if (stage.push_constants) push_block_ = stage.push_constants->name;
    for (const DescriptorBinding& b : stage.bindings) {
      if (b.set != 0)
        throw std::runtime_error("pipeline '" + name_ + "': binding '" + b.name + "' uses set " +
                                 std::to_string(b.set) + "; only set 0 (push descriptors) is supported");
      bool merged = false;
      for (DescriptorBinding& existing : bindings_)
        if (existing.binding == b.binding) {
          if (existing.type != b.type || existing.count != b.count || existing.name != b.name)
            throw InterfaceError("pipeline '" + name_ + "': binding " + std::to_string(b.binding) + " ('" + b.name +
                                 "') differs between stages");
          merged = true;
        } else if (existing.name == b.name) {
          throw InterfaceError("pipeline '" + name_ + "': '" + b.name + "' names bindings " +
                               std::to_string(existing.binding) + " and " + std::to_string(b.binding));
        }
      if (!merged) bindings_.push_back(b);
    }
  }
  // In binding order: the validation layer (1.3.239) lost track of pushed descriptors
  // whose binding came after a higher-numbered one in the layout.
  std::sort(bindings_.begin(), bindings_.end(),
            [](const DescriptorBinding& a, const DescriptorBinding& b) { return a.binding < b.binding; });
  std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
  for (const DescriptorBinding& b : bindings_)
    layout_bindings.push_back({b.binding, b.type, b.count, stages_, nullptr});
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  set_info.bindingCount = uint32_t(layout_bindings.size());
  set_info.pBindings = layout_bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &set_info, nullptr, &set_layout_));
  objects_->set_layout = set_layout_;
  ctx.set_name(set_layout_, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name_ + " set layout");

  VkPushConstantRange range{stages_, 0, kPushConstantBytes};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout_;
  layout_info.pushConstantRangeCount = push_block_.empty() ? 0 : 1;
  layout_info.pPushConstantRanges = &range;
  VK_CHECK(vkCreatePipelineLayout(ctx.device(), &layout_info, nullptr, &layout_));
  objects_->layout = layout_;
  ctx.set_name(layout_, VK_OBJECT_TYPE_PIPELINE_LAYOUT, name_ + " layout");
}

Pipeline Pipeline::create_compute(const Context& ctx, std::span<const uint32_t> spirv, const std::string& name) {
  Pipeline p;
  p.name_ = name;
  p.bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  ShaderReflection reflection = reflect_spirv(spirv);
  if (reflection.stage != VK_SHADER_STAGE_COMPUTE_BIT)
    throw std::runtime_error("pipeline '" + name + "': not a compute shader");
  p.local_size_ = reflection.local_size;
  p.create_layout(ctx, {reflection});
  VkShaderModule module = create_module(ctx, spirv, name);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = reflection.entry_point.c_str();
  info.layout = p.layout_;
  VkResult result = vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline_);
  ctx.destroy_named(module, VK_OBJECT_TYPE_SHADER_MODULE, vkDestroyShaderModule);
  VK_CHECK(result);
  p.objects_->pipeline = p.pipeline_;
  ctx.set_name(p.pipeline_, VK_OBJECT_TYPE_PIPELINE, name);
  return p;
}

static VkPipelineColorBlendAttachmentState blend_state(BlendMode mode) {
  VkPipelineColorBlendAttachmentState s{};
  s.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                     VK_COLOR_COMPONENT_A_BIT;
  if (mode == BlendMode::None) return s;
  s.blendEnable = VK_TRUE;
  s.colorBlendOp = s.alphaBlendOp = VK_BLEND_OP_ADD;
  switch (mode) {
    case BlendMode::Alpha:
      s.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      s.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      s.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      break;
    case BlendMode::PremultipliedAlpha:
      s.srcColorBlendFactor = s.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstColorBlendFactor = s.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      break;
    case BlendMode::Additive:
      s.srcColorBlendFactor = s.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      s.dstColorBlendFactor = s.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      break;
    case BlendMode::None: break;
  }
  return s;
}

Pipeline Pipeline::create_graphics(const Context& ctx, const GraphicsPipelineDesc& desc) {
  Pipeline p;
  p.name_ = desc.name;
  p.bind_point_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
  std::vector<const std::vector<uint32_t>*> sources = {&desc.vertex};
  if (!desc.geometry.empty()) sources.push_back(&desc.geometry);
  if (!desc.fragment.empty()) sources.push_back(&desc.fragment);
  std::vector<ShaderReflection> reflections;
  for (const auto* spirv : sources) reflections.push_back(reflect_spirv(*spirv));
  p.create_layout(ctx, reflections);

  std::vector<VkShaderModule> modules;
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  for (size_t i = 0; i < sources.size(); ++i) {
    modules.push_back(create_module(ctx, *sources[i], desc.name));
    VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stage.stage = reflections[i].stage;
    stage.module = modules.back();
    stage.pName = reflections[i].entry_point.c_str();
    stages.push_back(stage);
  }

  VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cull_mode;
  raster.frontFace = desc.front_face;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depth_test;
  depth.depthWriteEnable = desc.depth_write;
  depth.depthCompareOp = desc.depth_compare;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.color_formats.size(), blend_state(desc.blend));
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = uint32_t(blends.size());
  blend.pAttachments = blends.data();
  VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = uint32_t(desc.color_formats.size());
  rendering.pColorAttachmentFormats = desc.color_formats.data();
  rendering.depthAttachmentFormat = desc.depth_format;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = uint32_t(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = p.layout_;
  VkResult result = vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline_);
  for (VkShaderModule m : modules) ctx.destroy_named(m, VK_OBJECT_TYPE_SHADER_MODULE, vkDestroyShaderModule);
  VK_CHECK(result);
  p.objects_->pipeline = p.pipeline_;
  ctx.set_name(p.pipeline_, VK_OBJECT_TYPE_PIPELINE, desc.name);
  return p;
}

Pipeline::~Pipeline() { release(); }
Pipeline::Pipeline(Pipeline&& other) noexcept { *this = std::move(other); }

Pipeline& Pipeline::operator=(Pipeline&& other) noexcept {
  if (this != &other) {
    release();
    objects_ = std::move(other.objects_);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
    bind_point_ = other.bind_point_;
    stages_ = other.stages_;
    push_block_ = std::move(other.push_block_);
    bindings_ = std::move(other.bindings_);
    local_size_ = other.local_size_;
    name_ = std::move(other.name_);
  }
  return *this;
}

void Pipeline::release() {
  objects_.reset();
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
}

void Pipeline::bind(VkCommandBuffer cmd) const { vkCmdBindPipeline(cmd, bind_point_, pipeline_); }

void Pipeline::push_constants(VkCommandBuffer cmd, const StructLayout& layout, const void* data) const {
  if (push_block_ != layout.name)
    throw InterfaceError("pipeline '" + name_ + "': pushed " + layout.name + ", but its shaders' push constants are " +
                         (push_block_.empty() ? std::string("none") : push_block_));
  vkCmdPushConstants(cmd, layout_, stages_, 0, layout.size, data);
}

void Pipeline::dispatch_threads(VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z) const {
  auto groups = [](uint32_t n, uint32_t size) { return (n + size - 1) / size; };
  vkCmdDispatch(cmd, groups(x, local_size_[0]), groups(y, local_size_[1]), groups(z, local_size_[2]));
}

const DescriptorBinding& Pipeline::binding(std::string_view name) const {
  for (const DescriptorBinding& b : bindings_)
    if (b.name == name) return b;
  throw InterfaceError("pipeline '" + name_ + "' has no binding named '" + std::string(name) + "'");
}

// ---------------------------------------------------------------- Bindings

void Bindings::fail(const DescriptorBinding& binding, const std::string& problem) const {
  throw InterfaceError("pipeline '" + pipeline_.name() + "': binding '" + binding.name + "' (" +
                       std::to_string(binding.binding) + ") " + problem);
}

// Infos are stored in vectors reserved up front, so the pointers the writes keep stay valid.
VkWriteDescriptorSet& Bindings::add(const DescriptorBinding& binding, uint32_t count) {
  if (writes_.size() == kMaxBindingsPerPush) throw std::runtime_error("too many bindings in one push");
  if (buffers_.capacity() < kMaxInfosPerPush) {
    buffers_.reserve(kMaxInfosPerPush);
    images_.reserve(kMaxInfosPerPush);
  }
  if (buffers_.size() + images_.size() + count > kMaxInfosPerPush)
    throw std::runtime_error("pipeline '" + pipeline_.name() + "': too many descriptors in one push");
  if (count != binding.count)
    fail(binding, "has " + std::to_string(binding.count) + " elements, " + std::to_string(count) + " given");
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = binding.binding;
  write.descriptorCount = count;
  write.descriptorType = binding.type;
  writes_.push_back(write);
  return writes_.back();
}

// A buffer must hold the block's fixed part and, with a runtime array, at least one
// element (when its size is known).
void Bindings::check_buffer(const DescriptorBinding& binding, const BufferRange& buffer) const {
  if (binding.type != VK_DESCRIPTOR_TYPE_STORAGE_BUFFER && binding.type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
    fail(binding, "is not a buffer");
  if (buffer.buffer == VK_NULL_HANDLE) fail(binding, "is given no buffer");
  const uint64_t needed = uint64_t(binding.fixed_bytes) + binding.runtime_stride;
  if (buffer.size != VK_WHOLE_SIZE && buffer.size < needed)
    fail(binding, "needs at least " + std::to_string(needed) + " bytes, the buffer given has " +
                      std::to_string(buffer.size));
}

void Bindings::check_image_type(const DescriptorBinding& binding, bool has_sampler) const {
  const VkDescriptorType type = binding.type;
  if (type != VK_DESCRIPTOR_TYPE_STORAGE_IMAGE && type != VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE &&
      type != VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)
    fail(binding, "is not an image");
  if ((type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) != has_sampler)
    fail(binding, has_sampler ? "takes no sampler" : "needs a sampler");
}

Bindings& Bindings::buffer(std::string_view name, BufferRange buffer) {
  const DescriptorBinding& b = pipeline_.binding(name);
  check_buffer(b, buffer);
  VkWriteDescriptorSet& write = add(b, 1);
  buffers_.push_back({buffer.buffer, buffer.offset, buffer.size});
  write.pBufferInfo = &buffers_.back();
  return *this;
}

// One write for the whole array: lavapipe (Mesa 22.3) ignores dstArrayElement in
// pushed descriptor writes, so element-by-element writes all landed on element 0.
Bindings& Bindings::buffer_array(std::string_view name, std::span<const BufferRange> buffers) {
  const DescriptorBinding& b = pipeline_.binding(name);
  for (const BufferRange& buffer : buffers) check_buffer(b, buffer);
  VkWriteDescriptorSet& write = add(b, uint32_t(buffers.size()));
  write.pBufferInfo = buffers_.data() + buffers_.size();
  for (const BufferRange& buffer : buffers) buffers_.push_back({buffer.buffer, buffer.offset, buffer.size});
  return *this;
}

Bindings& Bindings::image(std::string_view name, VkImageView view, VkImageLayout layout, VkSampler sampler) {
  const DescriptorBinding& b = pipeline_.binding(name);
  check_image_type(b, sampler != VK_NULL_HANDLE);
  VkWriteDescriptorSet& write = add(b, 1);
  images_.push_back({sampler, view, layout});
  write.pImageInfo = &images_.back();
  return *this;
}

Bindings& Bindings::image_array(std::string_view name, std::span<const VkImageView> views,
                                std::span<const VkImageLayout> layouts) {
  if (views.size() != layouts.size()) throw std::invalid_argument("image_array: one layout per view");
  const DescriptorBinding& b = pipeline_.binding(name);
  check_image_type(b, false);
  VkWriteDescriptorSet& write = add(b, uint32_t(views.size()));
  write.pImageInfo = images_.data() + images_.size();
  for (size_t i = 0; i < views.size(); ++i) images_.push_back({VK_NULL_HANDLE, views[i], layouts[i]});
  return *this;
}

Bindings& Bindings::sampler(std::string_view name, VkSampler sampler) {
  const DescriptorBinding& b = pipeline_.binding(name);
  if (b.type != VK_DESCRIPTOR_TYPE_SAMPLER) fail(b, "is not a sampler");
  VkWriteDescriptorSet& write = add(b, 1);
  images_.push_back({sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED});
  write.pImageInfo = &images_.back();
  return *this;
}

void Bindings::push(VkCommandBuffer cmd) {
  ctx_.cmd_push_descriptor_set(cmd, pipeline_.bind_point(), pipeline_.layout(), 0, uint32_t(writes_.size()),
                               writes_.data());
}

const Pipeline& ComputeVariants::get(uint32_t value) const {
  auto found = pipelines_.find(value);
  if (found != pipelines_.end()) return found->second;
  auto source = spirv_.find(value);
  if (source == spirv_.end())
    throw std::invalid_argument("pipeline '" + name_ + "': no variant for " + std::to_string(value));
  return pipelines_.emplace(value, Pipeline::compute(*ctx_, source->second, name_)).first->second;
}

}  // namespace avsm::gpu
