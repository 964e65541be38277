// Independent plan checker; see plan_verifier.h. Nothing here calls into the planner
// except to print flag names in messages.
#include "plan_verifier.h"

#include <rendergraph/vk_names.h>

#include <algorithm>
#include <map>
#include <optional>

namespace rg_test {
namespace {

using Stages = VkPipelineStageFlags2;
using Accesses = VkAccessFlags2;
using rg::kInvalidIndex;

// ---------------------------------------------------------------------------------------
// Stage/access reasoning of our own.

constexpr Stages kPreRasterShaders =
    VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT |
    VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT | VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT |
    VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT | VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT;
constexpr Stages kTransferStages = VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_BLIT_BIT |
                                   VK_PIPELINE_STAGE_2_RESOLVE_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT;
constexpr Stages kVertexInput = VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT | VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT;
constexpr Stages kGraphicsStages =
    VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | kVertexInput | kPreRasterShaders | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;

constexpr Accesses kWriteBits = VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT |
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr Accesses kReadBits =
    VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT |
    VK_ACCESS_2_UNIFORM_READ_BIT | VK_ACCESS_2_INPUT_ATTACHMENT_READ_BIT | VK_ACCESS_2_SHADER_READ_BIT |
    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
    VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_MEMORY_READ_BIT |
    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;

// Umbrella bits stand for the bits they include.
Stages expand_stages(Stages stages) {
  if (stages & VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT) return ~Stages{0};
  if (stages & VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT) stages |= kGraphicsStages;
  if (stages & VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT) stages |= kPreRasterShaders;
  if (stages & VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT) stages |= kVertexInput;
  if (stages & VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT) stages |= kTransferStages;
  return stages;
}

Accesses expand_access(Accesses access) {
  if (access & VK_ACCESS_2_MEMORY_READ_BIT) access |= kReadBits;
  if (access & VK_ACCESS_2_MEMORY_WRITE_BIT) access |= kWriteBits;
  if (access & VK_ACCESS_2_SHADER_READ_BIT)
    access |= VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
  if (access & VK_ACCESS_2_SHADER_WRITE_BIT) access |= VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  return access;
}

bool stages_cover(Stages mask, Stages needed) { return (expand_stages(needed) & ~expand_stages(mask)) == 0; }
bool stages_meet(Stages a, Stages b) { return (expand_stages(a) & expand_stages(b)) != 0; }
bool access_covers(Accesses mask, Accesses needed) { return (expand_access(needed) & ~expand_access(mask)) == 0; }

// What one usage needs: stages, accesses, whether it writes, and the layouts it works in.
struct Need {
  Stages stages = 0;
  Accesses access = 0;
  bool write = false;
};

Need need_of(rg::Usage usage, rg::QueueType queue) {
  const Stages shader = queue == rg::QueueType::Compute
                            ? VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT
                            : kPreRasterShaders | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  const Stages tests = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  using U = rg::Usage;
  switch (usage) {
    case U::Sampled: return {shader, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, false};
    case U::StorageRead: return {shader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false};
    case U::StorageWrite: return {shader, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case U::StorageReadWrite:
      return {shader, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case U::UniformRead: return {shader, VK_ACCESS_2_UNIFORM_READ_BIT, false};
    case U::ColorAttachment:
      return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, true};
    case U::DepthAttachmentWrite:
      return {tests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
              true};
    case U::DepthAttachmentRead: return {tests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, false};
    case U::TransferSrc: return {kTransferStages, VK_ACCESS_2_TRANSFER_READ_BIT, false};
    case U::TransferDst: return {kTransferStages, VK_ACCESS_2_TRANSFER_WRITE_BIT, true};
    case U::IndirectRead: return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, false};
    case U::VertexRead:
      return {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, false};
    case U::IndexRead: return {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT, false};
    case U::HostRead: return {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, false};
    case U::Present: return {0, 0, false};
  }
  return {};
}

bool layout_works_for(VkImageLayout layout, rg::Usage usage) {
  using U = rg::Usage;
  auto any_of = [&](std::initializer_list<VkImageLayout> layouts) {
    return std::find(layouts.begin(), layouts.end(), layout) != layouts.end();
  };
  switch (usage) {
    case U::Sampled:
      return any_of({VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL,
                     VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL});
    case U::StorageRead:
    case U::StorageWrite:
    case U::StorageReadWrite:
    case U::HostRead: return layout == VK_IMAGE_LAYOUT_GENERAL;
    case U::ColorAttachment:
      return any_of({VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_GENERAL});
    case U::DepthAttachmentWrite:
      return any_of({VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL});
    case U::DepthAttachmentRead:
      return any_of({VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL,
                     VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_GENERAL});
    case U::TransferSrc: return any_of({VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL});
    case U::TransferDst: return any_of({VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL});
    case U::Present: return layout == VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    case U::UniformRead:
    case U::IndirectRead:
    case U::VertexRead:
    case U::IndexRead: return false;  // buffer usages
  }
  return false;
}

// ---------------------------------------------------------------------------------------
// Accesses as events on a timeline. Positions: barriers recorded before plan pass q sit at
// 2q, the pass's accesses at 2q+1, final barriers at 2N, the final state at 2N+1, the
// imported initial state at -1.

struct Event {
  int64_t pos = 0;
  Stages stages = 0;
  Accesses access = 0;
  bool write = false;
  // Layout transitions and imported read states: anything in their dst scope is already
  // ordered after them, and other stages may chain from any of their stages.
  bool sync_point = false;
  std::string what;
};

struct OpenAccesses {
  std::optional<Event> last_write;  // last write or sync point
  std::vector<Event> reads;         // reads since then
};

struct TimedBarrier {
  int64_t pos;
  const rg::Barrier* barrier;
};

struct Use {
  uint32_t position;
  const rg::AccessDecl* access;
  rg::QueueType queue;
  const std::string* pass_name;
};

struct Range {
  uint64_t begin, end;
};

std::string hex(uint64_t value) {
  char text[32];
  std::snprintf(text, sizeof text, "0x%llx", static_cast<unsigned long long>(value));
  return text;
}

class Verifier {
 public:
  Verifier(const rg::Graph& graph, const rg::CompiledPlan& plan, const rg::MemoryModel& memory)
      : graph_(graph), plan_(plan), memory_(memory) {}

  std::vector<std::string> run() {
    if (!check_pass_lists()) return problems_;
    collect_uses();
    check_dependencies();
    check_culling();
    check_placements();
    collect_barriers();
    check_hazards();
    problems_at_run_ = problems_.size();
    return problems_;
  }

  // Problems found since run() returned (check_shared_memory).
  std::vector<std::string> problems_after_run() const {
    return std::vector<std::string>(problems_.begin() + ptrdiff_t(problems_at_run_), problems_.end());
  }

  // After run(): what the frame leaves in resource r's memory (verify_frames).
  const std::vector<Event>& open_at_end(uint32_t r) const { return open_at_end_[r]; }
  VkImageLayout end_layout(uint32_t r) const { return end_layout_[r]; }

  // After run(): imports x and y share memory, at bytes `x_at` and `y_at` of it. Every
  // access to one that conflicts with an access to the other (overlapping bytes, either
  // writing) is ordered after it by a barrier on either, as if they were one resource;
  // a pass that writes one while it uses the other cannot be ordered at all.
  void check_shared_memory(uint32_t x, uint64_t x_at, uint32_t y, uint64_t y_at) {
    for (const Use& ux : uses_[x])
      for (const Use& uy : uses_[y]) {
        const Range bx = bytes_of(res(x), ux.access->range), by = bytes_of(res(y), uy.access->range);
        if (x_at + bx.begin >= y_at + by.end || y_at + by.begin >= x_at + bx.end) continue;
        if (!ux.access->writes && !uy.access->writes) continue;
        if (ux.position == uy.position) {
          problem("pass '" + *ux.pass_name + "' uses " + name(x) + " and " + name(y) +
                  ", which share memory, and writes one of them");
          continue;
        }
        const bool x_first = ux.position < uy.position;
        const Use& first = x_first ? ux : uy;
        const Use& second = x_first ? uy : ux;
        const Event earlier = event_of(first, 2 * int64_t{first.position} + 1);
        const Event later = event_of(second, 2 * int64_t{second.position} + 1);
        auto covers = [&](const TimedBarrier& tb) {
          const rg::Barrier& b = *tb.barrier;
          return tb.pos > earlier.pos && tb.pos < later.pos && src_covers(b, earlier) &&
                 stages_cover(b.dst_stages, later.stages) && (!earlier.write || access_covers(b.dst_access, later.access));
        };
        const bool ordered = std::any_of(barriers_[x].begin(), barriers_[x].end(), covers) ||
                             std::any_of(barriers_[y].begin(), barriers_[y].end(), covers) ||
                             std::any_of(global_barriers_.begin(), global_barriers_.end(), covers);
        if (!ordered)
          problem("hazard on the memory " + name(x) + " and " + name(y) + " share: " + later.what +
                  " is not ordered after " + earlier.what);
      }
  }

 private:
  const rg::Graph& graph_;
  const rg::CompiledPlan& plan_;
  const rg::MemoryModel& memory_;
  std::vector<std::string> problems_;
  size_t problems_at_run_ = 0;

  std::vector<uint32_t> position_;  // per declared pass, kInvalidIndex if culled
  std::vector<std::vector<Use>> uses_;  // per resource, in plan order
  std::vector<rg::UsageSet> usages_;
  std::vector<uint32_t> first_, last_;
  std::vector<std::vector<TimedBarrier>> barriers_;  // per resource
  std::vector<TimedBarrier> global_barriers_;
  std::vector<std::vector<Event>> open_at_end_;  // per resource, all bytes
  std::vector<VkImageLayout> end_layout_;        // per texture: its layout after the final barriers
  // While simulating one byte interval of a resource: its barriers, and its name in
  // messages (the resource's, plus the interval when accesses split it).
  const std::vector<TimedBarrier>* interval_barriers_ = nullptr;
  std::string subject_;
  std::vector<Range> ranges_;  // memory of placed transients (images rounded out to pages)

  void problem(std::string text) { problems_.push_back(std::move(text)); }
  const rg::ResourceDecl& res(uint32_t r) const { return graph_.resources()[r]; }
  std::string name(uint32_t r) const { return "'" + res(r).name + "'"; }
  std::string pass_name(uint32_t pass) const { return "'" + graph_.passes()[pass].name + "'"; }
  bool kept(uint32_t pass) const { return pass != kInvalidIndex && position_[pass] != kInvalidIndex; }
  int64_t end_pos() const { return 2 * static_cast<int64_t>(plan_.passes.size()); }

  // --- structure -------------------------------------------------------------------------

  bool check_pass_lists() {
    const auto& passes = graph_.passes();
    position_.assign(passes.size(), kInvalidIndex);
    std::vector<int> seen(passes.size(), 0);
    auto note = [&](const rg::PlannedPass& planned) {
      if (planned.pass_index >= passes.size()) {
        problem("plan names unknown pass #" + std::to_string(planned.pass_index));
        return false;
      }
      const rg::PassDecl& decl = passes[planned.pass_index];
      if (planned.name != decl.name || planned.queue != decl.queue)
        problem("plan pass #" + std::to_string(planned.pass_index) + " does not match its declaration");
      ++seen[planned.pass_index];
      return true;
    };
    for (uint32_t q = 0; q < plan_.passes.size(); ++q)
      if (note(plan_.passes[q])) position_[plan_.passes[q].pass_index] = q;
    for (const rg::PlannedPass& culled : plan_.culled_passes) note(culled);
    for (uint32_t p = 0; p < passes.size(); ++p)
      if (seen[p] != 1)
        problem("pass " + pass_name(p) + " appears " + std::to_string(seen[p]) + " times among planned and culled");
    if (plan_.resources.size() != graph_.resources().size()) problem("plan has a different resource count");
    return problems_.empty();
  }

  void collect_uses() {
    const size_t count = graph_.resources().size();
    uses_.assign(count, {});
    usages_.assign(count, {});
    first_.assign(count, kInvalidIndex);
    last_.assign(count, kInvalidIndex);
    for (uint32_t q = 0; q < plan_.passes.size(); ++q) {
      const rg::PassDecl& pass = graph_.passes()[plan_.passes[q].pass_index];
      for (const rg::AccessDecl& access : pass.accesses) {
        const uint32_t r = access.resource;
        uses_[r].push_back(Use{q, &access, pass.queue, &pass.name});
        usages_[r].insert(access.usages);
        if (first_[r] == kInvalidIndex) first_[r] = q;
        last_[r] = q;
      }
    }
    for (const rg::OutputDecl& output : graph_.outputs())
      if (first_[output.resource] != kInvalidIndex) last_[output.resource] = plan_.passes.size() - 1;
  }

  // Every read follows its producer (or an import) and comes before the next write.
  void check_dependencies() {
    for (uint32_t r = 0; r < uses_.size(); ++r) {
      const rg::ResourceDecl& resource = res(r);
      for (const Use& use : uses_[r]) {
        const rg::AccessDecl& a = *use.access;
        const std::string who = "pass '" + *use.pass_name + "'";
        if (a.reads) {
          if (a.read_version == 0 && !resource.imported) problem(who + " reads " + name(r) + " before any write");
          if (a.read_version == 0 && resource.imported && resource.kind == rg::ResourceKind::Texture &&
              resource.initial.layout == VK_IMAGE_LAYOUT_UNDEFINED)
            problem(who + " reads imported " + name(r) + " whose contents are undefined");
          const uint32_t producer = resource.writers[a.read_version];
          if (a.read_version > 0 && (!kept(producer) || position_[producer] >= use.position))
            problem(who + " reads " + name(r) + " version " + std::to_string(a.read_version) +
                    " but its producer " + pass_name(producer) + " does not run before it");
          if (a.read_version + 1 < resource.writers.size()) {
            const uint32_t next_writer = resource.writers[a.read_version + 1];
            if (kept(next_writer) && position_[next_writer] < use.position)
              problem(who + " reads " + name(r) + " after " + pass_name(next_writer) + " overwrote it");
          }
        }
        if (a.writes && a.written_version >= 2) {
          const uint32_t previous_writer = resource.writers[a.written_version - 1];
          if (kept(previous_writer) && position_[previous_writer] >= use.position)
            problem(who + " writes " + name(r) + " before the previous writer " + pass_name(previous_writer));
        }
      }
    }
  }

  // Anchors are kept; with culling on, nothing that is not needed is kept.
  void check_culling() {
    const auto& passes = graph_.passes();
    std::vector<bool> needed(passes.size(), false);
    for (uint32_t p = 0; p < passes.size(); ++p) {
      needed[p] = passes[p].side_effect;
      for (const rg::AccessDecl& a : passes[p].accesses) needed[p] = needed[p] || (a.writes && res(a.resource).imported);
    }
    for (const rg::OutputDecl& output : graph_.outputs()) {
      const uint32_t producer = res(output.resource).writers[output.version];
      if (producer != kInvalidIndex) needed[producer] = true;
    }
    for (uint32_t p = 0; p < passes.size(); ++p)
      if (needed[p] && !kept(p)) problem("anchored pass " + pass_name(p) + " was culled");
    // Close over "reads a version produced by": iterate to a fixpoint (graphs here are small).
    for (bool changed = true; changed;) {
      changed = false;
      for (uint32_t p = 0; p < passes.size(); ++p) {
        if (!needed[p]) continue;
        for (const rg::AccessDecl& a : passes[p].accesses) {
          // A write of a buffer range keeps the other bytes: it needs the version it replaces.
          const bool partial_write = a.writes && !a.range.whole();
          if (!a.reads && !partial_write) continue;
          const uint32_t version = a.reads ? a.read_version : a.written_version - 1;
          const uint32_t producer = res(a.resource).writers[version];
          if (producer != kInvalidIndex && !needed[producer]) needed[producer] = changed = true;
        }
      }
    }
    for (uint32_t p = 0; p < passes.size(); ++p) {
      if (plan_.options.culling && kept(p) && !needed[p]) problem("pass " + pass_name(p) + " is kept but unused");
      if (!plan_.options.culling && !kept(p)) problem("pass " + pass_name(p) + " culled with culling off");
    }
  }

  // --- memory ----------------------------------------------------------------------------

  void check_placements() {
    const uint64_t page = std::max<uint64_t>(memory_.buffer_image_granularity(), 1);
    ranges_.assign(graph_.resources().size(), Range{0, 0});
    std::vector<std::vector<uint32_t>> residents(plan_.heaps.size());
    for (uint32_t r = 0; r < graph_.resources().size(); ++r) {
      const rg::PlannedResource& planned = plan_.resources[r];
      const bool used = first_[r] != kInvalidIndex;
      if (planned.used != used || (used && (planned.first_pass != first_[r] || planned.last_pass != last_[r])))
        problem(name(r) + ": plan lifetime differs from the declaration");
      if (planned.usages != usages_[r]) problem(name(r) + ": plan usages differ from the declaration");
      const bool placed = used && !res(r).imported;
      if (!placed) {
        if (planned.heap != kInvalidIndex) problem(name(r) + " is placed but is imported or unused");
        continue;
      }
      if (planned.heap >= plan_.heaps.size()) {
        problem(name(r) + " is a used transient without a valid heap");
        continue;
      }
      const rg::MemoryRequirements req = res(r).kind == rg::ResourceKind::Texture
                                             ? memory_.texture(res(r).texture, usages_[r], res(r).name)
                                             : memory_.buffer(res(r).buffer, usages_[r], res(r).name);
      const rg::PlannedHeap& heap = plan_.heaps[planned.heap];
      if (planned.size != req.size) problem(name(r) + ": planned size differs from the memory model");
      if (planned.offset % req.alignment != 0) problem(name(r) + ": offset " + std::to_string(planned.offset) +
                                                       " is not aligned to " + std::to_string(req.alignment));
      if (heap.memory_type_bits == 0 || (heap.memory_type_bits & ~req.memory_type_bits) != 0)
        problem(name(r) + ": heap memory types " + hex(heap.memory_type_bits) + " not all allowed (" +
                hex(req.memory_type_bits) + ")");
      if (planned.offset + req.size > heap.size) problem(name(r) + " does not fit in its heap");
      Range range{planned.offset, planned.offset + req.size};
      if (res(r).kind == rg::ResourceKind::Texture) range = {range.begin / page * page, (range.end + page - 1) / page * page};
      ranges_[r] = range;
      residents[planned.heap].push_back(r);
    }
    for (const auto& heap : residents)
      for (size_t i = 0; i < heap.size(); ++i)
        for (size_t j = i + 1; j < heap.size(); ++j) check_overlap(heap[i], heap[j]);
  }

  bool alive_together(uint32_t a, uint32_t b) const { return first_[a] <= last_[b] && first_[b] <= last_[a]; }
  bool memory_overlaps(uint32_t a, uint32_t b) const {
    return ranges_[a].begin < ranges_[b].end && ranges_[b].begin < ranges_[a].end;
  }

  void check_overlap(uint32_t a, uint32_t b) {
    if (!memory_overlaps(a, b)) return;
    if (!plan_.options.aliasing) problem(name(a) + " and " + name(b) + " share memory with aliasing off");
    else if (alive_together(a, b))
      problem(name(a) + " and " + name(b) + " overlap in memory while both alive (passes " +
              std::to_string(first_[a]) + ".." + std::to_string(last_[a]) + " and " + std::to_string(first_[b]) +
              ".." + std::to_string(last_[b]) + ")");
  }

  // The resources that last occupied some byte of r's memory before r: the latest ended
  // first; an older one only counts for bytes no later one covers.
  std::vector<uint32_t> previous_occupants(uint32_t r) const {
    std::vector<uint32_t> candidates;
    for (uint32_t other = 0; other < graph_.resources().size(); ++other)
      if (other != r && ranges_[other].end > ranges_[other].begin && plan_.resources[other].heap == plan_.resources[r].heap &&
          last_[other] < first_[r] && memory_overlaps(r, other))
        candidates.push_back(other);
    std::sort(candidates.begin(), candidates.end(), [&](uint32_t a, uint32_t b) { return last_[a] > last_[b]; });
    std::vector<uint32_t> latest;
    std::vector<Range> covered;
    for (uint32_t other : candidates) {
      const Range overlap{std::max(ranges_[r].begin, ranges_[other].begin), std::min(ranges_[r].end, ranges_[other].end)};
      if (!fully_covered(overlap, covered)) latest.push_back(other);
      covered.push_back(overlap);
    }
    return latest;
  }

  static bool fully_covered(Range range, std::vector<Range> covered) {
    std::sort(covered.begin(), covered.end(), [](Range a, Range b) { return a.begin < b.begin; });
    uint64_t reached = range.begin;
    for (const Range& c : covered)
      if (c.begin <= reached) reached = std::max(reached, c.end);
    return reached >= range.end;
  }

  // --- hazards ---------------------------------------------------------------------------

  void collect_barriers() {
    barriers_.assign(graph_.resources().size(), {});
    global_barriers_.clear();
    auto add = [&](const rg::Barrier& b, int64_t pos) {
      if (b.is_global()) {
        global_barriers_.push_back({pos, &b});
        if (b.old_layout != VK_IMAGE_LAYOUT_UNDEFINED || b.new_layout != VK_IMAGE_LAYOUT_UNDEFINED)
          problem("a global barrier carries a layout transition");
      } else if (b.resource >= barriers_.size()) {
        problem("a barrier names unknown resource #" + std::to_string(b.resource));
      } else {
        barriers_[b.resource].push_back({pos, &b});
      }
    };
    for (uint32_t q = 0; q < plan_.passes.size(); ++q)
      for (const rg::Barrier& b : plan_.passes[q].barriers) add(b, 2 * int64_t{q});
    for (const rg::Barrier& b : plan_.final_barriers) add(b, end_pos());
  }

  static bool src_covers(const rg::Barrier& b, const Event& earlier) {
    if (earlier.sync_point) return stages_meet(b.src_stages, earlier.stages);
    return stages_cover(b.src_stages, earlier.stages) &&
           (!earlier.write || access_covers(b.src_access, earlier.access & kWriteBits));
  }

  // Is the access `later` (at `pos`, on resource r) ordered after `earlier`?
  bool ordered(const Event& earlier, const Event& later, uint32_t r) const {
    const bool needs_visibility = earlier.write || earlier.sync_point;
    if (earlier.sync_point && stages_cover(earlier.stages, later.stages) && access_covers(earlier.access, later.access))
      return true;
    auto covers = [&](const TimedBarrier& tb) {
      const rg::Barrier& b = *tb.barrier;
      return tb.pos > earlier.pos && tb.pos < later.pos && src_covers(b, earlier) &&
             stages_cover(b.dst_stages, later.stages) && (!needs_visibility || access_covers(b.dst_access, later.access));
    };
    (void)r;
    return std::any_of(interval_barriers_->begin(), interval_barriers_->end(), covers) ||
           std::any_of(global_barriers_.begin(), global_barriers_.end(), covers);
  }

  void require_ordered(const Event& earlier, const Event& later, uint32_t r, const char* hazard) {
    if (!ordered(earlier, later, r))
      problem(std::string(hazard) + " hazard on " + subject_ + ": " + later.what + " is not ordered after " +
              earlier.what);
  }

  struct Track {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    OpenAccesses open;
    bool accessed = false;
    bool first_use_transition_checked = false;
  };

  void check_hazards() {
    open_at_end_.assign(graph_.resources().size(), {});
    end_layout_.assign(graph_.resources().size(), VK_IMAGE_LAYOUT_UNDEFINED);
    // Earlier-starting resources first: aliasing checks need the final state of the
    // resources that occupied the memory before.
    std::vector<uint32_t> order;
    for (uint32_t r = 0; r < graph_.resources().size(); ++r)
      if (first_[r] != kInvalidIndex || res(r).imported) order.push_back(r);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      const int64_t fa = res(a).imported ? -1 : first_[a], fb = res(b).imported ? -1 : first_[b];
      return fa < fb;
    });
    for (uint32_t r : order) simulate(r);
  }

  // The bytes a buffer range covers; a texture is one unit (whole-resource barriers).
  static Range bytes_of(const rg::ResourceDecl& resource, const rg::BufferRange& range) {
    if (resource.kind == rg::ResourceKind::Texture || range.whole())
      return {0, resource.kind == rg::ResourceKind::Texture ? 1 : resource.buffer.size};
    return {range.offset, range.offset + range.size};
  }

  // Cuts the resource into the intervals that every access and barrier either covers
  // completely or misses, and checks each interval like a resource of its own.
  void simulate(uint32_t r) {
    const Range all = bytes_of(res(r), {});
    std::vector<uint64_t> cuts = {all.begin, all.end};
    auto cut = [&](Range range) {
      cuts.push_back(range.begin);
      cuts.push_back(range.end);
    };
    for (const Use& use : uses_[r]) cut(bytes_of(res(r), use.access->range));
    for (const TimedBarrier& tb : barriers_[r]) {
      const Range range = bytes_of(res(r), tb.barrier->range);
      if (range.end > all.end || range.begin >= range.end) problem("a barrier on " + name(r) + " leaves the buffer");
      cut(range);
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    for (size_t i = 0; i + 1 < cuts.size() && cuts[i + 1] <= all.end; ++i)
      simulate_interval(r, Range{cuts[i], cuts[i + 1]}, cuts.size() > 2);
  }

  void simulate_interval(uint32_t r, Range bytes, bool split) {
    const rg::ResourceDecl& resource = res(r);
    const bool texture = resource.kind == rg::ResourceKind::Texture;
    auto touches = [&](const rg::BufferRange& range) {
      const Range touched = bytes_of(resource, range);
      return touched.begin < bytes.end && bytes.begin < touched.end;
    };
    std::vector<TimedBarrier> barriers;
    for (const TimedBarrier& tb : barriers_[r])
      if (touches(tb.barrier->range)) barriers.push_back(tb);
    std::stable_sort(barriers.begin(), barriers.end(),
                     [](const TimedBarrier& a, const TimedBarrier& b) { return a.pos < b.pos; });
    interval_barriers_ = &barriers;
    subject_ = name(r);
    if (split) subject_ += " bytes [" + std::to_string(bytes.begin) + ", " + std::to_string(bytes.end) + ")";

    Track track;
    if (resource.imported) start_imported(track, resource);
    // Walk barriers and accesses in timeline order (barriers of a pass precede its access).
    size_t next_barrier = 0;
    auto barriers_until = [&](int64_t pos) {
      for (; next_barrier < barriers.size() && barriers[next_barrier].pos <= pos; ++next_barrier)
        apply_barrier(r, track, barriers[next_barrier]);
    };
    for (const Use& use : uses_[r]) {
      if (!touches(use.access->range)) continue;
      const int64_t pos = 2 * int64_t{use.position} + 1;
      barriers_until(pos);
      access(r, track, use, pos, texture);
    }
    barriers_until(end_pos());
    if (resource.imported) finish_imported(r, track, resource);
    if (texture) end_layout_[r] = track.layout;
    std::vector<Event>& open = open_at_end_[r];
    open.insert(open.end(), track.open.reads.begin(), track.open.reads.end());
    if (track.open.last_write) open.push_back(*track.open.last_write);
  }

  static void start_imported(Track& track, const rg::ResourceDecl& resource) {
    const rg::ImportState& initial = resource.initial;
    if (resource.kind == rg::ResourceKind::Texture) track.layout = initial.layout;
    if (initial.stages == 0 && initial.access == 0) return;
    Event event{-1, initial.stages, initial.access, (initial.access & kWriteBits) != 0, false, "the imported state"};
    if (event.write) {
      track.open.last_write = event;
      return;
    }
    track.open.reads.push_back(event);  // later writes wait for these readers
    event.sync_point = true;            // and the data is visible exactly to this scope
    track.open.last_write = event;
  }

  void apply_barrier(uint32_t r, Track& track, const TimedBarrier& tb) {
    const rg::Barrier& b = *tb.barrier;
    if (res(r).kind == rg::ResourceKind::Buffer) {
      if (b.old_layout != VK_IMAGE_LAYOUT_UNDEFINED || b.new_layout != VK_IMAGE_LAYOUT_UNDEFINED)
        problem("buffer " + subject_ + " has a barrier with image layouts");
      return;
    }
    // old_layout must be the current layout; UNDEFINED (discard) only before a transient's
    // first use, when there are no contents to lose.
    const bool transition = b.old_layout != b.new_layout;
    const bool first_use = !res(r).imported && !track.accessed;
    const bool discard_ok = transition && b.old_layout == VK_IMAGE_LAYOUT_UNDEFINED && first_use;
    if (b.old_layout != track.layout && !discard_ok)
      problem("barrier on " + name(r) + " from " + rg::layout_name(b.old_layout) + " but it is in " +
              rg::layout_name(track.layout) + (b.old_layout == VK_IMAGE_LAYOUT_UNDEFINED ? " (discards contents)" : ""));
    if (!transition) return;  // only provides ordering
    // A transition rewrites the memory: everything open must be in this barrier's src.
    std::vector<Event> open = track.open.reads;
    if (track.open.last_write) open.push_back(*track.open.last_write);
    if (first_use) {
      for (uint32_t previous : previous_occupants(r))
        open.insert(open.end(), open_at_end_[previous].begin(), open_at_end_[previous].end());
      track.first_use_transition_checked = true;
    }
    for (const Event& earlier : open)
      if (!src_covers(b, earlier))
        problem("layout transition of " + name(r) + " is not ordered after " + earlier.what +
                (first_use ? " (memory aliasing)" : ""));
    track.layout = b.new_layout;
    track.open.last_write = Event{tb.pos, b.dst_stages, b.dst_access, true, true,
                                  "the layout transition to " + rg::layout_name(b.new_layout)};
    track.open.reads.clear();
  }

  // A pass's access as an event at `pos`: what its usages need, named after the pass.
  static Event event_of(const Use& use, int64_t pos) {
    Event event{pos, 0, 0, false, false, ""};
    std::string usage_names;
    use.access->usages.for_each([&](rg::Usage usage) {
      const Need need = need_of(usage, use.queue);
      event.stages |= need.stages;
      event.access |= need.access;
      event.write |= need.write;
      usage_names += (usage_names.empty() ? "" : "+") + std::string(rg::to_string(usage));
    });
    event.what = "pass '" + *use.pass_name + "' (" + usage_names + ")";
    return event;
  }

  void access(uint32_t r, Track& track, const Use& use, int64_t pos, bool texture) {
    const Event later = event_of(use, pos);
    if (texture)
      use.access->usages.for_each([&](rg::Usage usage) {
        if (!layout_works_for(track.layout, usage))
          problem(name(r) + " is in " + rg::layout_name(track.layout) + " when pass '" + *use.pass_name +
                  "' uses it as " + rg::to_string(usage));
      });

    if (!track.accessed && !res(r).imported) {
      if (!later.write) problem(later.what + " reads " + subject_ + " before anything wrote it");
      if (!track.first_use_transition_checked)
        for (uint32_t previous : previous_occupants(r))
          for (const Event& earlier : open_at_end_[previous]) require_ordered(earlier, later, r, "aliasing");
    }
    track.accessed = true;
    settle(r, track, later);
  }

  // RAW/WAW against the last write, WAR against the reads since; then record `later`.
  void settle(uint32_t r, Track& track, const Event& later) {
    if (track.open.last_write) require_ordered(*track.open.last_write, later, r, later.write ? "WAW" : "RAW");
    if (later.write)
      for (const Event& read : track.open.reads) require_ordered(read, later, r, "WAR");
    if (later.write) {
      track.open.last_write = later;
      track.open.reads.clear();
    } else {
      track.open.reads.push_back(later);
    }
  }

  void finish_imported(uint32_t r, Track& track, const rg::ResourceDecl& resource) {
    const rg::ImportState& wanted = resource.final_state;
    if (resource.kind == rg::ResourceKind::Texture && wanted.layout != VK_IMAGE_LAYOUT_UNDEFINED &&
        track.layout != wanted.layout)
      problem(name(r) + " ends in " + rg::layout_name(track.layout) + " instead of its final " +
              rg::layout_name(wanted.layout));
    if (wanted.stages == 0 && wanted.access == 0) return;
    const Event final_state{end_pos() + 1, wanted.stages, wanted.access, (wanted.access & kWriteBits) != 0, false,
                            "the final state"};
    // The next user waits on the final stages only: reads in other stages must be ordered
    // before them, even when the final state itself only reads.
    if (!final_state.write)
      for (const Event& read : track.open.reads)
        if (!stages_cover(final_state.stages, read.stages)) require_ordered(read, final_state, r, "final-state WAR");
    settle(r, track, final_state);
  }
};

}  // namespace

std::vector<std::string> verify_plan(const rg::Graph& graph, const rg::CompiledPlan& plan,
                                     const rg::MemoryModel& memory) {
  return Verifier(graph, plan, memory).run();
}

namespace {

// What a frame left in a piece of imported memory for the frames after it.
struct Carried {
  uint64_t begin = 0, end = 0;
  size_t frame = 0;
  std::string left_by;  // "frame <i>'s '<import>'"
  bool texture = false;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  std::optional<rg::ImportState> final_state;  // the frame's final state, if it named one
  std::vector<Event> open;                     // otherwise: the accesses it left open
};

bool is_none(const rg::ImportState& state) { return state.stages == 0 && state.access == 0; }

// Problems with `initial` (import `what`) as a claim about `before`.
// `drained`: the frame that left `before` had completed.
void check_claim(bool drained, const rg::ImportState& initial, const Carried& before, const std::string& what,
                 std::vector<std::string>& problems) {
  const std::string prefix = what + " starts in a state " + before.left_by + " did not leave: ";
  if (before.texture && initial.layout != VK_IMAGE_LAYOUT_UNDEFINED && initial.layout != before.layout)
    problems.push_back(prefix + "layout " + rg::layout_name(initial.layout) + " instead of " +
                       rg::layout_name(before.layout));
  if (drained) return;
  if (before.final_state) {
    const rg::ImportState& left = *before.final_state;
    if (left.stages == VK_PIPELINE_STAGE_2_HOST_BIT) return;  // drained by the host's wait
    if (is_none(initial)) {
      problems.push_back(prefix + "nothing pending, after a final state in " + rg::stage_names(left.stages));
      return;
    }
    if (!stages_meet(initial.stages, left.stages))
      problems.push_back(prefix + "stages " + rg::stage_names(initial.stages) + " do not chain to the final " +
                         rg::stage_names(left.stages));
    const bool claims_visible = (initial.access & kWriteBits) == 0;
    if (claims_visible && (!stages_cover(left.stages, initial.stages) || !access_covers(left.access, initial.access)))
      problems.push_back(prefix + "it claims " + rg::access_names(initial.access) + " in " +
                         rg::stage_names(initial.stages) + " visible, the final state made " +
                         rg::access_names(left.access) + " in " + rg::stage_names(left.stages) + " visible");
    return;
  }
  for (const Event& open : before.open) {
    const bool write = open.write || open.sync_point;
    if (!stages_cover(initial.stages, open.stages) ||
        (write && !access_covers(initial.access, open.access & kWriteBits)))
      problems.push_back(prefix + open.what + " is still open and not inside " + rg::stage_names(initial.stages) + " / " +
                         rg::access_names(initial.access));
  }
}

// `left` replaces what it covers of the older pieces; the rest of them stays.
void leave(std::vector<Carried>& pieces, Carried left) {
  std::vector<Carried> kept;
  for (Carried& piece : pieces) {
    if (piece.end <= left.begin || left.end <= piece.begin) {
      kept.push_back(std::move(piece));
      continue;
    }
    if (piece.begin < left.begin) {
      Carried head = piece;
      head.end = left.begin;
      kept.push_back(std::move(head));
    }
    if (piece.end > left.end) {
      Carried tail = piece;
      tail.begin = left.end;
      kept.push_back(std::move(tail));
    }
  }
  kept.push_back(std::move(left));
  pieces = std::move(kept);
}

}  // namespace

std::vector<std::string> verify_frames(const std::vector<PlannedFrame>& frames, const rg::MemoryModel& memory) {
  std::vector<std::string> problems;
  std::map<uint64_t, std::vector<Carried>> carried;  // per object, disjoint pieces
  for (size_t f = 0; f < frames.size(); ++f) {
    const rg::Graph& graph = *frames[f].graph;
    const std::string frame = "frame " + std::to_string(f) + ": ";
    Verifier verifier(graph, *frames[f].plan, memory);
    std::vector<std::string> own = verifier.run();
    for (std::string& p : own) problems.push_back(frame + p);
    if (!own.empty()) continue;  // the frame's own state is not to be trusted

    struct Import {
      uint32_t resource;
      PhysicalRange range;
    };
    std::vector<Import> imports;
    for (uint32_t r = 0; r < graph.resources().size() && r < frames[f].memory.size(); ++r)
      if (graph.resources()[r].imported && frames[f].memory[r]) imports.push_back({r, *frames[f].memory[r]});
    auto name = [&](const Import& i) { return "'" + graph.resources()[i.resource].name + "'"; };
    auto overlap = [](const PhysicalRange& a, uint64_t begin, uint64_t end) { return a.begin < end && begin < a.end; };

    for (size_t a = 0; a < imports.size(); ++a)
      for (size_t b = a + 1; b < imports.size(); ++b) {
        const Import &x = imports[a], &y = imports[b];
        if (x.range.object == y.range.object && overlap(x.range, y.range.begin, y.range.end))
          verifier.check_shared_memory(x.resource, x.range.begin, y.resource, y.range.begin);
      }
    for (const std::string& p : verifier.problems_after_run()) problems.push_back(frame + p);

    for (const Import& i : imports)
      for (const Carried& piece : carried[i.range.object])
        if (overlap(i.range, piece.begin, piece.end))
          check_claim(piece.frame < frames[f].completed_before, graph.resources()[i.resource].initial, piece, frame + name(i), problems);

    for (const Import& i : imports) {
      const rg::ResourceDecl& decl = graph.resources()[i.resource];
      Carried left{i.range.begin, i.range.end, f, "frame " + std::to_string(f) + "'s " + name(i),
                   decl.kind == rg::ResourceKind::Texture, verifier.end_layout(i.resource), std::nullopt, {}};
      if (is_none(decl.final_state))
        left.open = verifier.open_at_end(i.resource);
      else
        left.final_state = decl.final_state;
      if (left.texture && decl.final_state.layout != VK_IMAGE_LAYOUT_UNDEFINED) left.layout = decl.final_state.layout;
      leave(carried[i.range.object], std::move(left));
    }
  }
  return problems;
}

}  // namespace rg_test
