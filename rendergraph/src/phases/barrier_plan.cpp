// Phase 6: barrier plan. Walks the passes in order, tracking per resource what later
// accesses must wait for, and emits one sync2 barrier per (pass, resource) when needed:
//
//   read after write    wait for the write, unless it is already visible to this
//                       stage/access (read-after-read in the same layout: no barrier)
//   write after read    wait for ALL reads since the last write (execution dependency)
//   write after write   wait for the write (memory dependency)
//   layout change       behaves as a write: waits for everything, then later readers in
//                       other stages wait for the transition
//   aliasing            a transient's first use waits for the last accesses of the
//                       resources that occupied its memory before, starting from UNDEFINED
//   buffer ranges       each byte range of a buffer has its own state: an access waits
//                       only for earlier accesses of the bytes it touches, with one barrier
//                       per range of bytes in the same state (adjacent equal ones merged)
//
// Every barrier names the earlier accesses directly in its src scope (not only through
// chains of barriers): plans are easy to read and to check.
//
// All passes are treated as one queue in plan order, whatever their QueueType (see plan.h).
#include <algorithm>
#include <map>

#include "phases.h"

namespace rg::detail {
namespace {

struct Scope {
  VkPipelineStageFlags2 stages;
  VkAccessFlags2 access;

  bool operator==(const Scope&) const = default;
};

struct SyncState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // textures only
  // The last write or layout transition: every later access is ordered after these.
  VkPipelineStageFlags2 write_stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 write_access = VK_ACCESS_2_NONE;  // write bits to make available
  // Stages that read since the last write: a later write waits for all of them.
  VkPipelineStageFlags2 read_stages = VK_PIPELINE_STAGE_2_NONE;
  // Scopes the last write is already visible to: reads inside one need no barrier.
  std::vector<Scope> visible;

  bool operator==(const SyncState&) const = default;
};

// The state of one resource per byte range. Textures, and buffers only used whole, keep
// one segment; accesses to buffer ranges split it at their edges. Segments are sorted,
// contiguous and cover [0, extent); equal neighbours are merged again after each access.
class ResourceSync {
 public:
  struct Segment {
    uint64_t begin, end;
    SyncState state;
  };

  void reset(uint64_t extent, SyncState state) { segments_.assign(1, Segment{0, extent, std::move(state)}); }

  // Calls fn(segment) for each segment inside [begin, end), after splitting at the edges.
  template <class Fn>
  void update(uint64_t begin, uint64_t end, Fn&& fn) {
    split_at(begin);
    split_at(end);
    for (Segment& segment : segments_)
      if (segment.begin >= begin && segment.end <= end) fn(segment);
    merge_equal_neighbours();
  }

  // Everything pending on any byte, as one state (what memory reusing it must wait for).
  SyncState pending() const {
    SyncState all;
    for (const Segment& segment : segments_) {
      all.write_stages |= segment.state.write_stages;
      all.write_access |= segment.state.write_access;
      all.read_stages |= segment.state.read_stages;
    }
    return all;
  }

 private:
  void split_at(uint64_t at) {
    for (size_t i = 0; i < segments_.size(); ++i) {
      Segment& segment = segments_[i];
      if (segment.begin >= at || segment.end <= at) continue;
      Segment tail{at, segment.end, segment.state};
      segment.end = at;
      segments_.insert(segments_.begin() + static_cast<std::ptrdiff_t>(i) + 1, std::move(tail));
      return;
    }
  }

  void merge_equal_neighbours() {
    size_t kept = 0;
    for (size_t i = 1; i < segments_.size(); ++i) {
      if (segments_[i].state == segments_[kept].state) {
        segments_[kept].end = segments_[i].end;
      } else if (++kept != i) {
        segments_[kept] = std::move(segments_[i]);  // (never onto itself: that empties `visible`)
      }
    }
    segments_.resize(kept + 1);
  }

  std::vector<Segment> segments_;
};

bool is_visible(const SyncState& state, const AccessNeeds& need) {
  return std::any_of(state.visible.begin(), state.visible.end(), [&](const Scope& scope) {
    return (need.stages & ~scope.stages) == 0 && (need.access & ~scope.access) == 0;
  });
}

// An imported resource starts in its declared state. A read-only state still has to be
// waited for by later writes, and its data is only known to be visible to that scope.
SyncState imported_state(const ImportState& initial, bool is_texture) {
  SyncState state;
  state.layout = is_texture ? initial.layout : VK_IMAGE_LAYOUT_UNDEFINED;
  if (const VkAccessFlags2 writes = write_access_bits(initial.access)) {
    state.write_stages = initial.stages;
    state.write_access = writes;
  } else if (initial.stages != VK_PIPELINE_STAGE_2_NONE) {
    state.write_stages = initial.stages;
    state.read_stages = initial.stages;
    state.visible.push_back({initial.stages, initial.access});
  }
  return state;
}

// A transient's first use after others used its memory: wait for all of their last
// accesses; contents are discarded (layout UNDEFINED).
SyncState state_after_occupants(const std::vector<uint32_t>& occupants, const std::vector<ResourceSync>& sync) {
  SyncState state;
  for (uint32_t previous : occupants) {
    const SyncState pending = sync[previous].pending();
    state.write_stages |= pending.write_stages;
    state.write_access |= pending.write_access;
    state.read_stages |= pending.read_stages;
  }
  return state;
}

// Updates `state` for an access needing `need`; returns true when `barrier` must be
// recorded before it (barrier.resource/aliased are filled in by the caller).
bool synchronise(SyncState& state, const AccessNeeds& need, bool is_texture, Barrier& barrier) {
  const bool transition = is_texture && need.layout != state.layout;
  barrier.dst_stages = need.stages;
  barrier.dst_access = need.access;
  barrier.old_layout = state.layout;
  barrier.new_layout = is_texture ? need.layout : VK_IMAGE_LAYOUT_UNDEFINED;

  if (!transition && !need.writes) {  // read in the current layout
    const bool wait = state.write_stages != VK_PIPELINE_STAGE_2_NONE && !is_visible(state, need);
    state.read_stages |= need.stages;
    if (!wait) return false;
    barrier.src_stages = state.write_stages;
    barrier.src_access = state.write_access;
    state.visible.push_back({need.stages, need.access});
    return true;
  }

  barrier.src_stages = state.write_stages | state.read_stages;
  barrier.src_access = state.write_access;
  if (need.writes) {
    state.write_stages = need.stages;
    state.write_access = write_access_bits(need.access);
    state.read_stages = VK_PIPELINE_STAGE_2_NONE;
    state.visible.clear();
  } else {
    // A transition for a read acts as a write at need.stages. Keeping the earlier write in
    // the state makes later barriers name it directly too (it is already available).
    state.write_stages |= need.stages;
    state.read_stages = need.stages;
    state.visible.assign(1, Scope{need.stages, need.access});
  }
  state.layout = barrier.new_layout;
  return transition || barrier.src_stages != VK_PIPELINE_STAGE_2_NONE;
}

// An imported resource's final state is a promise to its next user (the next frame's
// import, the presentation engine, the host): it is in that layout, its last write is
// visible to that scope, and everything the graph did is ordered before those stages, so
// that the next user's barrier, waiting on exactly those stages, waits for the whole
// graph. A final layout of UNDEFINED keeps whatever layout the graph left.
bool finish(SyncState& state, const ImportState& final_state, bool is_texture, Barrier& barrier) {
  AccessNeeds need{final_state.stages, final_state.access, final_state.layout,
                   write_access_bits(final_state.access) != 0};
  if (!is_texture || need.layout == VK_IMAGE_LAYOUT_UNDEFINED) need.layout = state.layout;
  if (need.stages == VK_PIPELINE_STAGE_2_NONE && need.access == VK_ACCESS_2_NONE && need.layout == state.layout)
    return false;  // ImportState::none(): no promise
  // Reads in other stages would escape the next user's wait: order them like a write would.
  if ((state.read_stages & ~need.stages) != 0) need.writes = true;
  return synchronise(state, need, is_texture, barrier);
}

Barrier full_barrier() {
  Barrier barrier;
  barrier.src_stages = barrier.dst_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.src_access = barrier.dst_access = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  return barrier;
}

// Which resource last occupied each byte range of one heap. A first use waits only for
// the latest occupants of its bytes: older ones were already waited for by the resource
// that replaced them, and that wait chains into this one through the replacing resource's
// own barriers (each of which names its last write stages in its src scope).
class HeapOccupancy {
 public:
  // Makes `resource` the occupant of [begin, end); returns the previous occupants.
  std::vector<uint32_t> occupy(uint64_t begin, uint64_t end, uint32_t resource) {
    std::vector<uint32_t> previous;
    auto it = segments_.lower_bound(begin);
    if (it != segments_.begin()) {
      auto before = std::prev(it);
      if (before->second.end > begin) {  // straddles `begin`: split it there
        Segment inside = before->second;
        before->second.end = begin;
        it = segments_.emplace_hint(it, begin, inside);
      }
    }
    while (it != segments_.end() && it->first < end) {
      previous.push_back(it->second.resource);
      if (it->second.end > end) segments_.emplace_hint(std::next(it), end, it->second);  // keep the tail
      it = segments_.erase(it);
    }
    segments_.emplace(begin, Segment{end, resource});
    std::sort(previous.begin(), previous.end());
    previous.erase(std::unique(previous.begin(), previous.end()), previous.end());
    return previous;
  }

 private:
  struct Segment {
    uint64_t end;
    uint32_t resource;
  };
  std::map<uint64_t, Segment> segments_;  // begin -> segment, non-overlapping
};

// The bytes of a resource the segments of ResourceSync count: a buffer's size; a texture
// is one unit (its barriers cover all mips and layers).
uint64_t extent(const ResourceDecl& resource) {
  return resource.kind == ResourceKind::Buffer ? resource.buffer.size : 1;
}

bool same_but_range(Barrier a, const Barrier& b) {
  a.range = b.range;
  return a == b;
}

// Appends `barrier` for bytes [begin, end) of its resource, extending the previous barrier
// (from index `first` on) instead when that one ends at `begin` and is otherwise the same.
void add_range_barrier(std::vector<Barrier>& barriers, size_t first, Barrier barrier, uint64_t begin, uint64_t end) {
  if (barriers.size() > first) {
    Barrier& previous = barriers.back();
    if (previous.range.offset + previous.range.size == begin && same_but_range(previous, barrier)) {
      previous.range.size = end - previous.range.offset;
      return;
    }
  }
  barrier.range = {begin, end - begin};
  barriers.push_back(std::move(barrier));
}

// Barriers over the whole resource say so (as before ranges existed, and as the executor's
// whole-resource Vulkan barriers do).
void mark_whole_ranges(std::vector<Barrier>& barriers, size_t first, uint64_t resource_extent) {
  for (size_t i = first; i < barriers.size(); ++i)
    if (barriers[i].range.offset == 0 && barriers[i].range.size == resource_extent) barriers[i].range = {};
}

// Synchronises every segment that `range` touches with `sync_one`, appending one barrier
// per run of bytes that needs the same one.
template <class SyncOne>
void synchronise_range(ResourceSync& sync, const ResourceDecl& resource, BufferRange range, const Barrier& proto,
                       std::vector<Barrier>& barriers, SyncOne&& sync_one) {
  const uint64_t size = extent(resource);
  const uint64_t begin = resource.kind == ResourceKind::Buffer ? range.offset : 0;
  const uint64_t end = resource.kind == ResourceKind::Buffer ? range.end(size) : size;
  const size_t first = barriers.size();
  sync.update(begin, end, [&](ResourceSync::Segment& segment) {
    Barrier barrier = proto;
    if (sync_one(segment.state, barrier)) add_range_barrier(barriers, first, std::move(barrier), segment.begin, segment.end);
  });
  mark_whole_ranges(barriers, first, size);
}

}  // namespace

void plan_barriers(CompileState& state) {
  const auto& passes = state.graph.passes();
  const auto& resources = state.graph.resources();

  std::vector<ResourceSync> sync(resources.size());
  for (uint32_t r = 0; r < resources.size(); ++r)
    sync[r].reset(extent(resources[r]), resources[r].imported ? imported_state(resources[r].initial,
                                                                              resources[r].kind == ResourceKind::Texture)
                                                              : SyncState{});
  std::vector<HeapOccupancy> occupancy(state.heaps.size());

  state.barriers.assign(state.order.size(), {});
  for (uint32_t position = 0; position < state.order.size(); ++position) {
    std::vector<Barrier>& barriers = state.barriers[position];
    if (state.options.serial_full_barriers && position > 0) barriers.push_back(full_barrier());

    const PassDecl& pass = passes[state.order[position]];
    for (const AccessDecl& access : pass.accesses) {
      const uint32_t r = access.resource;
      const bool is_texture = resources[r].kind == ResourceKind::Texture;
      Barrier barrier;
      barrier.resource = r;
      // (A transient's first pass accesses it once: reading version 0 is refused.)
      if (!resources[r].imported && state.lifetimes[r].first == position) {
        const Placement& placement = state.placements[r];
        barrier.aliased = occupancy[placement.heap].occupy(placement.offset, placement.offset + placement.footprint, r);
        sync[r].reset(extent(resources[r]), state_after_occupants(barrier.aliased, sync));
      }
      const AccessNeeds need = access_needs(access, pass.queue, resources[r].kind);
      synchronise_range(sync[r], resources[r], access.range, barrier, barriers,
                        [&](SyncState& bytes, Barrier& b) { return synchronise(bytes, need, is_texture, b); });
    }
  }

  state.final_barriers.clear();
  for (uint32_t r = 0; r < resources.size(); ++r) {
    if (!resources[r].imported) continue;
    Barrier barrier;
    barrier.resource = r;
    const bool is_texture = resources[r].kind == ResourceKind::Texture;
    synchronise_range(sync[r], resources[r], BufferRange{}, barrier, state.final_barriers,
                      [&](SyncState& bytes, Barrier& b) { return finish(bytes, resources[r].final_state, is_texture, b); });
  }
}

}  // namespace rg::detail
