#pragma once
// Realises a compiled plan on a Vulkan device: allocates the heaps, binds the
// transient images and buffers at their planned offsets, records the planned
// sync2 barriers, and wraps every pass in a debug label and a GPU timing scope.
// The plan (and the transient resources) are reused while the graph's shape is
// unchanged from the last frame.
//
// One frame in flight: record() may replace transient resources, so the command
// buffer of the previous record() must have completed before the next call.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/pass_context.h>

#include <memory>
#include <unordered_map>
#include <string>
#include <vector>

#include "gpu/gpu_timer.h"
#include "gpu/resources.h"

namespace rg::vulkan {

// Imports an engine image or buffer into `graph`, carrying it: its description comes
// from the object, and the executor finds it without a bind(). It must outlive the
// graph's execution.
TextureHandle import(Graph& graph, std::string name, const avsm::gpu::Image& image, ImportState initial,
                     ImportState final_state);
BufferHandle import(Graph& graph, std::string name, const avsm::gpu::Buffer& buffer, ImportState initial,
                    ImportState final_state);

// MemoryModel answered by the driver (vkGetDevice*MemoryRequirements).
class DeviceMemoryModel final : public MemoryModel {
 public:
  explicit DeviceMemoryModel(const avsm::gpu::Context& ctx) : ctx_(ctx) {}
  // Throw avsm::gpu::ResourceLimitError for what the device cannot hold.
  MemoryRequirements texture(const TextureDesc& desc, UsageSet usages, const std::string& name) const override;
  MemoryRequirements buffer(const BufferDesc& desc, UsageSet usages, const std::string& name) const override;
  uint64_t buffer_image_granularity() const override;

 private:
  const avsm::gpu::Context& ctx_;
};

struct PassTiming {
  std::string name;
  QueueType queue = QueueType::Graphics;
  double gpu_ms = 0;
  double cpu_record_ms = 0;
};

class Executor {
 public:
  // `timed_passes`: how many passes the timer first has room for; it grows with the graphs
  // recorded.
  Executor(avsm::gpu::Context& ctx, avsm::gpu::TimestampMode timestamps, uint32_t timed_passes = 64);
  ~Executor();

  // Physical resources behind imported handles declared without one (rg::vulkan::import
  // carries its resource; a bind() here takes precedence). An import may also carry a
  // plain avsm::gpu::BufferRange with an explicit size (a buffer the engine does not own,
  // e.g. one named by a shadow pass list).
  void bind(TextureHandle texture, const avsm::gpu::Image& image);
  void bind(BufferHandle buffer, const avsm::gpu::Buffer& buffer_object);

  // Compiles the graph (or reuses the last plan), then records the whole frame.
  void record(const Graph& graph, VkCommandBuffer cmd, const CompileOptions& options = {});

  // After the recorded command buffer has completed.
  std::vector<PassTiming> read_timings() const;

  const CompiledPlan& plan() const { return plan_; }
  bool plan_was_reused() const { return plan_reused_; }
  const DeviceMemoryModel& memory_model() const { return memory_model_; }
  avsm::gpu::TimestampMode timestamp_mode() const { return timer_.mode(); }

  // The transient image / buffer placed for a plan resource (tests and debugging).
  const avsm::gpu::Image* transient_image(uint32_t resource) const;
  const avsm::gpu::Buffer* transient_buffer(uint32_t resource) const;

 private:
  void start_binding(uint32_t graph_id);
  void realise_transients();
  void resolve_imports(const Graph& graph);
  void record_barriers(VkCommandBuffer cmd, const std::vector<Barrier>& barriers) const;

  avsm::gpu::Context& ctx_;
  DeviceMemoryModel memory_model_;
  avsm::gpu::GpuTimer timer_;
  CompiledPlan plan_;
  bool has_plan_ = false;
  bool plan_reused_ = false;
  std::vector<avsm::gpu::MemoryHeap> heaps_;
  std::vector<std::unique_ptr<avsm::gpu::Image>> transient_images_;    // by resource index
  std::vector<std::unique_ptr<avsm::gpu::Buffer>> transient_buffers_;  // by resource index
  std::vector<const avsm::gpu::Image*> images_;                        // by resource index
  std::vector<avsm::gpu::BufferRange> buffers_;                        // by resource index
  // Imports bound for the graph with id bound_graph_id_, by resource index.
  uint32_t bound_graph_id_ = 0;
  std::vector<const avsm::gpu::Image*> imported_images_;
  std::vector<const avsm::gpu::Buffer*> imported_buffers_;
  std::vector<avsm::gpu::BufferRange> carried_ranges_;  // imports carrying a plain range, by resource index
  std::vector<double> cpu_record_ms_;
};

}  // namespace rg::vulkan
