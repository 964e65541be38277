#include "gpu/gpu_timer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "gpu/barriers.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/rendering.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "gpu/vk_check.h"
#include "shared/gpu/spin.h"

namespace avsm::gpu {

const char* to_string(TimestampMode mode) { return mode == TimestampMode::Exact ? "exact" : "end-to-end"; }

// Query layout: 0 = frame start; scope i uses 1 + 2i (begin) and 2 + 2i (end);

static uint32_t begin_query(uint32_t scope) { return 1 + 2 * scope; }
static uint32_t end_query(uint32_t scope) { return 2 + 2 * scope; }
static uint32_t query_count(uint32_t max_scopes) { return 1 + 2 * max_scopes; }

void GpuTimer::write_timestamp(VkCommandBuffer cmd, uint32_t query) {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, query);
  // See the header: resolves the timestamp now on lavapipe; orders nothing.
  if (mode_ == TimestampMode::EndToEnd)
    memory_barrier(cmd, {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE},
                   {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE});
}

GpuTimer::GpuTimer(const Context& ctx, uint32_t scopes, TimestampMode mode) : ctx_(ctx), mode_(mode) {
  if (ctx.info().timestamp_valid_bits == 0) throw std::runtime_error("the device's queue has no timestamps");
  create_pool(std::max(scopes, 1u));
}

GpuTimer::~GpuTimer() { ctx_.destroy_named(pool_, VK_OBJECT_TYPE_QUERY_POOL, vkDestroyQueryPool); }

void GpuTimer::create_pool(uint32_t scopes) {
  if (pool_) ctx_.destroy_named(pool_, VK_OBJECT_TYPE_QUERY_POOL, vkDestroyQueryPool);
  pool_ = VK_NULL_HANDLE;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = query_count(scopes);
  VK_CHECK(vkCreateQueryPool(ctx_.device(), &info, nullptr, &pool_));
  ctx_.set_name(pool_, VK_OBJECT_TYPE_QUERY_POOL, "gpu timer");
  max_scopes_ = scopes;
}

void GpuTimer::begin_frame(VkCommandBuffer cmd, uint32_t scopes) {
  // Twice what is asked for, so that a graph that grows by a pass at a time does not make a
  // pool each frame.
  if (scopes > max_scopes_) create_pool(std::max(scopes, 2 * max_scopes_));
  names_.clear();
  vkCmdResetQueryPool(cmd, pool_, 0, query_count(max_scopes_));
  write_timestamp(cmd, 0);
}

uint32_t GpuTimer::begin_scope(VkCommandBuffer cmd, const std::string& name) {
  if (names_.size() == max_scopes_)
    throw std::logic_error("GpuTimer: scope '" + name + "' is one more than the " + std::to_string(max_scopes_) +
                           " begin_frame() was told of");
  uint32_t scope = uint32_t(names_.size());
  names_.push_back(name);
  if (mode_ == TimestampMode::Exact) write_timestamp(cmd, begin_query(scope));
  return scope;
}

void GpuTimer::end_scope(VkCommandBuffer cmd, uint32_t scope) {
  write_timestamp(cmd, end_query(scope));
}

std::vector<ScopeTiming> GpuTimer::read_scopes() const {
  std::vector<uint64_t> ticks(query_count(max_scopes_), 0);
  // Queries that were never written (begins in EndToEnd mode) stay unavailable,
  // so read each one we use on its own and wait for it.
  auto read = [&](uint32_t query) {
    VK_CHECK(vkGetQueryPoolResults(ctx_.device(), pool_, query, 1, sizeof(uint64_t), &ticks[query], sizeof(uint64_t),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  };
  read(0);
  for (uint32_t s = 0; s < names_.size(); ++s) {
    if (mode_ == TimestampMode::Exact) read(begin_query(s));
    read(end_query(s));
  }
  double ns_per_tick = ctx_.info().timestamp_period_ns;
  std::vector<ScopeTiming> out;
  uint64_t previous_end = ticks[0];
  for (uint32_t s = 0; s < names_.size(); ++s) {
    uint64_t begin = mode_ == TimestampMode::Exact ? ticks[begin_query(s)] : previous_end;
    uint64_t end = ticks[end_query(s)];
    double ms = end > begin ? double(end - begin) * ns_per_tick * 1e-6 : 0.0;
    out.push_back({names_[s], ms});
    previous_end = end;
  }
  return out;
}

// --------------------------------------------------------------- calibration

using shared::SpinPush;  // shaders/shared/gpu/spin.h

TimestampCalibration calibrate_timestamps(const Context& ctx, const ShaderLibrary& shaders) {
  TimestampCalibration result;
  const uint32_t invocations = 1u << 14;
  Buffer values = Buffer::create(ctx, {invocations * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       MemoryLocation::DeviceLocal, "timestamp calibration values"});
  ImageDesc target_desc;
  target_desc.width = target_desc.height = 64;
  target_desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  target_desc.name = "timestamp calibration target";
  Image target = Image::create(ctx, target_desc);
  Pipeline spin = Pipeline::compute(ctx, shaders.load("shaders/gpu/spin.comp"), "timestamp calibration");
  GpuTimer timer(ctx, 1, TimestampMode::Exact);

  // Grow the workload until the host sees at least 20 ms, so submission
  // overhead cannot hide the dispatch on a fast GPU.
  for (uint32_t iterations = 256; iterations <= (1u << 26); iterations *= 4) {
    auto start = std::chrono::steady_clock::now();
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      clear_with_rendering(cmd, target);  // timestamps go late only after rendering
      timer.begin_frame(cmd, 1);
      uint32_t scope = timer.begin_scope(cmd, "spin");
      spin.bind(cmd);
      Bindings(ctx, spin).buffer("Values", values).push(cmd);
      spin.push_constants(cmd, SpinPush{iterations, invocations});
      spin.dispatch_threads(cmd, invocations);
      timer.end_scope(cmd, scope);
    });
    double host_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    result.dispatch_ms_host = host_ms;
    result.dispatch_ms_timestamps = timer.read_scopes()[0].gpu_ms;
    if (host_ms >= 20.0) break;
  }
  // Honest timestamps see most of the host time; late ones see almost none.
  bool late = result.dispatch_ms_timestamps < 0.25 * result.dispatch_ms_host;
  result.mode = late ? TimestampMode::EndToEnd : TimestampMode::Exact;

  std::string forced = env_or_empty("AVSM_TIMESTAMP_MODE");
  if (forced == "exact") result.mode = TimestampMode::Exact;
  if (forced == "end-to-end") result.mode = TimestampMode::EndToEnd;
  return result;
}

}  // namespace avsm::gpu
