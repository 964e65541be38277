#pragma once
// A paged light's pages on the CPU (shadow.layout "paged"; the layout the GPU reads is
// shaders/shared/pages.h): which page of which level of which face holds which slot of
// the light's fixed pool, what the receivers asked for, and which pages to build next.
// A point light's six faces are six virtual maps that share one pool: a face that sees
// nothing holds only its coarsest page, and a busy face takes the slots it needs.
//
// Each frame the camera's receivers mark the pages their lookups read (request bits,
// read back when the frame completes: add_requests()). The next frame declared builds
// what plan_builds() picks: requested pages that have no slot or whose contents are
// stale, coarsest level first, so that a lookup whose page is still missing finds the
// finest coarser one. A page keeps its slot until the pool needs it for a page
// requested now: then the page least recently requested gives it up. The coarsest
// level is one page, always resident, so every lookup finds some level.
//
// A directional light's table keeps clipmap windows (shared/pages.h): its finest levels
// hold only the pages around the camera (move_window()), so that its map may cover a
// large scene at a fine virtual resolution with a small table.
//
// When requests outgrow the pool, the pages that do not fit are counted (unserved)
// and served by coarser levels, and a level-of-detail bias grows until the requests
// fit in about 85% of the pool; it shrinks back when they would fit again, even where a
// quarter level asks for 1.7x the pages. Either move is made in one frame.
//
// A frame visits only the requested entries (their request bits, a few among many words),
// the faces' roots and the pool's resident pages: its CPU cost follows the requests and
// the pool, not the virtual resolution (bench/pages/run.sh).
#include <glm/vec2.hpp>

#include "passes/shadows/uv_rect.h"

#include <bit>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace avsm::passes {

// Where a page sits: its level (0 the finest), its place in that level's grid, and its
// face (a point light's cube face; 0 for a light of one map).
struct PageKey {
  uint32_t level = 0;
  glm::uvec2 page{0u};
  uint32_t face = 0;
  bool operator==(const PageKey&) const = default;
};

// A page the frame builds into `slot` (its table word is already set).
struct PageBuild {
  uint32_t entry = 0;
  PageKey key;
  uint32_t slot = 0;
};

// Calls visit(i) for each set bit i of `bits` (bit i of word i / 32) below `count`: request
// bits, a few set among many words.
template <class Visit>
void for_each_set_bit(std::span<const uint32_t> bits, uint32_t count, Visit&& visit) {
  for (uint32_t word = 0; word < bits.size() && word * 32 < count; ++word)
    for (uint32_t rest = bits[word]; rest != 0; rest &= rest - 1) {
      const uint32_t i = word * 32 + uint32_t(std::countr_zero(rest));
      if (i < count) visit(i);
    }
}

// One frame's figures of a paged map (memory.json, the report, the viewer's panel).
struct PageStats {
  uint32_t slots = 0;        // the pool's size in pages
  uint32_t requested = 0;    // pages the receivers asked for (the last frame read back)
  uint32_t resident = 0;     // pages holding a slot after this frame's builds
  uint32_t built = 0;        // pages this frame built
  uint32_t invalidated = 0;  // pages whose contents went stale since the last frame
  uint32_t evicted = 0;      // pages that gave their slot to another this frame, or left a clipmap window
  uint32_t pending = 0;      // pages the frame's receivers asked for that it did not hold (coarser ones stood in)
  uint32_t unserved = 0;     // requested pages the pool could not hold (overflow)
  float lod_bias = 0.0f;     // the bias that keeps requests within the pool (levels)
  bool settling = false;     // the last requests moved the bias: the next frame asks for other pages
  bool operator==(const PageStats&) const = default;
};

class PageTable {
 public:
  // Throws std::invalid_argument unless page_size divides virtual_resolution (both
  // powers of two), slots >= 1, faces >= 1 and window is 0 or a power of two. `fallback_level`:
  // the coarsest level receivers ask for (passes/shadows/shadow_settings.h), so the bias
  // never grows past it (further would not shrink the requests); the last level when not
  // given. `faces` virtual maps of that size share the pool (their entries one face after
  // another). `window`: pages per side of a clipmap level's window (0: whole levels).
  PageTable(uint32_t virtual_resolution, uint32_t page_size, uint32_t slots, uint32_t fallback_level = ~0u,
            uint32_t faces = 1, uint32_t window = 0);

  uint32_t virtual_resolution() const { return virtual_resolution_; }
  uint32_t fallback_level() const { return fallback_level_; }
  uint32_t page_size() const { return page_size_; }
  uint32_t levels() const { return levels_; }
  uint32_t entries() const { return uint32_t(pages_.size()); }  // every face's
  uint32_t face_entries() const { return face_entries_; }
  uint32_t slots() const { return slots_; }
  uint32_t window_pages() const { return window_; }
  // Throws std::out_of_range for a page outside the map, or outside its level's window.
  uint32_t entry(const PageKey& key) const;
  bool has_entry(const PageKey& key) const;
  PageKey key(uint32_t entry) const;

  // The level-0 texel the clipmap windows are centred on (the camera's).
  glm::uvec2 window_centre() const { return window_centre_; }
  // Moves the windows to `centre`: the pages that leave a window give up their slot and
  // their entry to the pages that come in; returns how many resident pages left.
  uint32_t move_window(glm::uvec2 centre);

  // The request bits of a completed frame, per face: bit i of word i / 32 of a face's
  // span asks for that face's entry i, under the windows centred on `centre` (where
  // they were when the frame marked them). A table of one face may take its span alone.
  void add_requests(std::span<const std::span<const uint32_t>> faces, glm::uvec2 centre);
  void add_requests(std::span<const std::span<const uint32_t>> faces) { add_requests(faces, window_centre_); }
  void add_requests(std::span<const uint32_t> bits) { add_requests(std::span(&bits, 1)); }
  // Every page of `level` counts as asked for from now on (whatever the requests say).
  void require_level(uint32_t level);
  // The pages the next frame builds: at most `budget` (0: every one that fits the pool).
  std::vector<PageBuild> plan_builds(uint32_t budget);
  // A page whose contents are stale (what it covers changed): it leaves the table (the
  // root excepted, which is rebuilt first) and is built again when next requested.
  void invalidate(uint32_t entry);
  void invalidate_all();
  // Invalidates every resident page of `face` whose window (widened by a texel of its
  // level: hair ribbons are widened to a texel) overlaps one of `rects` (that face's uv);
  // returns how many.
  uint32_t invalidate_overlapping(std::span<const UvRect> rects, uint32_t face = 0);
  // The part of the map's uv square that page `key` covers, widened by `margin_texels`
  // texels of its level on every side.
  UvRect window(const PageKey& key, float margin_texels = 0.0f) const;

  // The page table as the GPU reads it: a word per entry, 0 or slot + 1; per face, the
  // words of its entries (its own table in the atlas; the slots are the shared pool's).
  const std::vector<uint32_t>& table_words() const { return table_; }
  std::vector<uint32_t> face_table_words(uint32_t face) const;
  bool resident(uint32_t entry) const { return pages_.at(entry).slot != kNoSlot; }
  // Requested pages that are missing or stale (after add_requests(): the next frame has
  // pages to build, or cannot hold them).
  bool has_pending_requests() const;
  // Every requested page is resident and current, at a settled bias: a capture may
  // write the frame.
  bool converged() const { return stats_.pending == 0 && stats_.unserved == 0 && !stats_.settling; }
  const PageStats& stats() const { return stats_; }
  // Counts the changes to the table and the builds planned: what reads the map may skip
  // a revision it has already read.
  uint64_t revision() const { return revision_; }
  float lod_bias() const { return lod_bias_; }

 private:
  static constexpr uint32_t kNoSlot = ~0u;
  struct Page {
    uint32_t slot = kNoSlot;
    bool current = false;    // built since it last went stale
    bool requested = false;  // in the last frame's requests
    uint64_t last_request = 0;
  };
  // A face's coarsest page: always resident.
  bool is_root(uint32_t entry) const { return entry % face_entries_ == face_entries_ - 1; }
  uint32_t root(uint32_t face) const { return (face + 1) * face_entries_ - 1; }
  uint32_t level_of(uint32_t entry) const;
  // The entries that hold a slot, in ascending order (per frame the table visits these,
  // the requested ones and the roots, never every entry: O(slots + requests)).
  std::vector<uint32_t> resident_entries() const;
  bool needs_build(uint32_t entry) const;
  // entry() and key() with the windows centred on `centre`; kNoEntry outside them.
  static constexpr uint32_t kNoEntry = ~0u;
  uint32_t entry_at(const PageKey& key, glm::uvec2 centre) const;
  PageKey key_at(uint32_t entry, glm::uvec2 centre) const;
  // `faces`' request bits marked under windows centred on `centre`, as entries of today's.
  std::vector<std::vector<uint32_t>> requests_in_window(std::span<const std::span<const uint32_t>> faces,
                                                        glm::uvec2 centre) const;
  void assign(uint32_t entry, uint32_t slot);
  void release(uint32_t entry);
  void adapt_lod_bias();
  bool overflowed_lately(float bias) const;

  uint32_t virtual_resolution_, page_size_, levels_, slots_, faces_, window_;
  glm::uvec2 window_centre_{0u};
  uint32_t face_entries_ = 0;
  uint32_t fallback_level_ = 0;  // also the most the bias grows to, in levels
  std::vector<uint32_t> level_first_;  // entry of each level's first page
  std::vector<Page> pages_;
  std::vector<uint32_t> requested_;  // entries whose Page::requested is set, ascending
  std::vector<uint32_t> table_;
  std::vector<uint32_t> free_slots_;
  std::vector<uint32_t> slot_owner_;  // entry per slot, or kNoSlot
  uint64_t request_clock_ = 0;
  uint32_t invalidated_since_plan_ = 0;
  uint32_t left_window_since_plan_ = 0;
  uint64_t revision_ = 0;
  float lod_bias_ = 0.0f;
  // Per bias (in quarter levels) the requests last seen at it, and when (request_clock_):
  // the bias does not come back down to one that overflowed lately.
  struct SeenRequests {
    uint32_t requested = 0;
    uint64_t clock = 0;
  };
  std::map<int, SeenRequests> seen_at_bias_;
  uint32_t required_level_ = ~0u;
  PageStats stats_;
};

}  // namespace avsm::passes
