// Shadows::record(): the frame's shadow work recorded into the host's command buffer, and
// the lookup's descriptor layout and buffers as plain Vulkan values (avsm/shadows.h). The
// host sees no rendergraph type: inside, record() declares the frame's pass list into a
// graph of its own (add_to_graph) and records it with the engine's Vulkan executor, which
// places the barriers between the passes and owns the transient memory.
#include <rendergraph/vulkan/executor.h>

#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "avsm/shadows.h"
#include "avsm/shadows_rendergraph.h"
#include "gpu/barriers.h"
#include "gpu/context.h"

namespace avsm {

namespace {

constexpr const char* kPassList = "avsm::Shadows::pass_list: ";

std::invalid_argument record_error(const std::string& what) {
  return std::invalid_argument("avsm::Shadows::record: " + what);
}

VkDescriptorBufferInfo whole(VkBuffer buffer) { return {buffer, 0, VK_WHOLE_SIZE}; }

VkDescriptorBufferInfo region(const PassBufferRange& range) { return {range.buffer, range.offset, range.size}; }

}  // namespace

ShadowLookupBuffers lookup_buffers(const ShadowLookupResources& lookup) {
  const auto or_unused = [&](const PassBufferRange& range) {
    return range.buffer ? region(range) : whole(lookup.unused_buffer);
  };
  return {region(lookup.parameters), or_unused(lookup.atlas), or_unused(lookup.list_heads),
          or_unused(lookup.list_nodes), or_unused(lookup.page_request_bits)};
}

std::array<VkDescriptorSetLayoutBinding, 5> shadow_lookup_layout(const ShadowLookupBindings& bindings,
                                                                 VkShaderStageFlags stages) {
  const std::set<uint32_t> distinct{bindings.parameters, bindings.atlas, bindings.list_heads, bindings.list_nodes,
                                    bindings.page_requests};
  if (distinct.size() != 5)
    throw std::invalid_argument("avsm::shadow_lookup_layout: bindings " + std::to_string(bindings.parameters) + ", " +
                                std::to_string(bindings.atlas) + ", " + std::to_string(bindings.list_heads) + ", " +
                                std::to_string(bindings.list_nodes) + ", " + std::to_string(bindings.page_requests) +
                                " (parameters, atlas, list_heads, list_nodes, page_requests) must be five different "
                                "numbers");
  if (stages == 0)
    throw std::invalid_argument("avsm::shadow_lookup_layout: stages is 0; give the stages of the shaders that "
                                "include common/shadow_lookup.glsl");
  const auto entry = [&](uint32_t binding) {
    return VkDescriptorSetLayoutBinding{binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr};
  };
  return {entry(bindings.parameters), entry(bindings.atlas), entry(bindings.list_heads), entry(bindings.list_nodes),
          entry(bindings.page_requests)};
}

std::array<VkWriteDescriptorSet, 5> ShadowLookupBuffers::writes(VkDescriptorSet set,
                                                                const ShadowLookupBindings& bindings) const {
  const auto write = [&](uint32_t binding, const VkDescriptorBufferInfo& info) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &info;
    return w;
  };
  return {write(bindings.parameters, parameters), write(bindings.atlas, atlas),
          write(bindings.list_heads, list_heads), write(bindings.list_nodes, list_nodes),
          write(bindings.page_requests, page_requests)};
}

// One executor per frame slot: an executor's transients belong to the frame it last
// recorded, which may still run while another slot records.
struct Shadows::Recorder {
  explicit Recorder(gpu::Context& context) : context(context) {}
  rg::vulkan::Executor& executor(uint32_t slot) {
    if (executors.size() <= slot) executors.resize(slot + 1);
    if (!executors[slot])
      executors[slot] = std::make_unique<rg::vulkan::Executor>(context, gpu::TimestampMode::EndToEnd);
    return *executors[slot];
  }
  gpu::Context& context;
  std::vector<std::unique_ptr<rg::vulkan::Executor>> executors;
};

std::shared_ptr<Shadows::Recorder> Shadows::make_recorder(gpu::Context& context) {
  return std::make_shared<Recorder>(context);
}

ShadowLookupBuffers Shadows::record(VkCommandBuffer cmd, const ShadowFrame& frame) {
  if (cmd == VK_NULL_HANDLE) throw record_error("cmd is VK_NULL_HANDLE");
  if (frame.casters_written.access != VK_ACCESS_2_NONE && frame.casters_written.stages == VK_PIPELINE_STAGE_2_NONE)
    throw record_error("frame.casters_written has access but no stages: give the stages of the writes (or NONE "
                       "for both when the casters are already visible)");
  if (frame.lookup_read_stages == VK_PIPELINE_STAGE_2_NONE)
    throw record_error("frame.lookup_read_stages is 0: give the shader stages that read the shadows");
  ShadowPassList list;
  try {
    list = pass_list(frame.camera, frame.casters, frame.frame_slot);
  } catch (const std::invalid_argument& e) {
    // pass_list's checks name its own arguments; here they are fields of `frame`.
    const std::string what = e.what();
    throw record_error(what.rfind(kPassList, 0) == 0 ? "frame." + what.substr(std::string(kPassList).size()) : what);
  }
  rg::Graph graph;
  add_to_graph(graph, list);
  // The graph knows neither the host's writes to the casters nor the host's reads of its
  // outputs (its imports end readable by graphics shaders only): two global barriers cover
  // them. The first waits for the casters' writes (read in several stages: index and
  // vertex input, shaders) and for the previous frame's lookups, which read the maps this
  // frame rebuilds; the last makes the frame's writes visible to the host's lookups.
  gpu::memory_barrier(cmd, {frame.casters_written.stages | frame.lookup_read_stages, frame.casters_written.access},
                      {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT});
  recorder_->executor(frame.frame_slot).record(graph, cmd);
  // (Paged lights: the lookups also write the request bits the frame cleared. The fog's
  // composite reads its grid in the same stages.)
  gpu::memory_barrier(cmd, {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT},
                      {frame.lookup_read_stages, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT});
  ShadowLookupBuffers buffers = lookup_buffers(list.lookup);
  buffers.fog_parameters = region(list.fog.parameters);
  buffers.fog_grid = region(list.fog.grid);
  return buffers;
}

}  // namespace avsm
