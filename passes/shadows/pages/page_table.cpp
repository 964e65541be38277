#include "passes/shadows/pages/page_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "shared/pages.h"

namespace avsm::passes {

namespace {

// Requests within this share of the pool leave the bias alone; above it the bias grows.
constexpr float kPoolHigh = 0.85f;
constexpr float kBiasStep = 0.25f;
// A quarter level less asks for about 1.4x the pages in theory, but up to 1.7x in the
// default scene at 640x360 (the pages at the edges of each level's band on screen). The
// bias comes down only as far as this worst case keeps the requests under kPoolHigh.
constexpr float kGrowthPerStep = 1.7f;
// Below this share the bias shrinks: one step down stays under kPoolHigh.
constexpr float kPoolLow = kPoolHigh / kGrowthPerStep;
// Where a growing bias aims (at 4x fewer pages per level): between kPoolLow and kPoolHigh.
constexpr float kPoolTarget = 0.7f;

bool is_power_of_two(uint32_t x) { return x != 0 && (x & (x - 1)) == 0; }

}  // namespace

PageTable::PageTable(uint32_t virtual_resolution, uint32_t page_size, uint32_t slots, uint32_t fallback_level,
                     uint32_t faces, uint32_t window)
    : virtual_resolution_(virtual_resolution), page_size_(page_size), slots_(slots), faces_(faces), window_(window) {
  if (!is_power_of_two(virtual_resolution) || !is_power_of_two(page_size) || page_size > virtual_resolution)
    throw std::invalid_argument("page table: a virtual resolution of " + std::to_string(virtual_resolution) +
                                " texels does not split into pages of " + std::to_string(page_size));
  if (slots == 0) throw std::invalid_argument("page table: a pool of no pages");
  if (faces == 0) throw std::invalid_argument("page table: no faces");
  if (window != 0 && !is_power_of_two(window))
    throw std::invalid_argument("page table: a window of " + std::to_string(window) + " pages is not a power of two");
  levels_ = shared::page_level_count(virtual_resolution, page_size);
  fallback_level_ = std::min(fallback_level, levels_ - 1);
  for (uint32_t level = 0; level <= levels_; ++level)
    level_first_.push_back(shared::page_table_level_first(virtual_resolution, page_size, window, level));
  face_entries_ = level_first_.back();
  pages_.resize(size_t(face_entries_) * faces);
  table_.assign(pages_.size(), shared::kPageAbsent);
  slot_owner_.assign(slots, kNoSlot);
  for (uint32_t s = slots; s-- > 0;) free_slots_.push_back(s);  // slot 0 handed out first
  stats_.slots = slots;
}

uint32_t PageTable::entry_at(const PageKey& key, glm::uvec2 centre) const {
  const uint32_t grid = shared::page_grid(virtual_resolution_, page_size_, key.level);
  if (key.level >= levels_ || key.page.x >= grid || key.page.y >= grid || key.face >= faces_) return kNoEntry;
  const uint32_t local = shared::page_table_entry(virtual_resolution_, page_size_, window_, key.level, key.page, centre);
  return local == shared::kNoPageEntry ? kNoEntry : key.face * face_entries_ + local;
}

uint32_t PageTable::entry(const PageKey& key) const {
  const uint32_t e = entry_at(key, window_centre_);
  if (e == kNoEntry)
    throw std::out_of_range("page table: no page (" + std::to_string(key.page.x) + ", " + std::to_string(key.page.y) +
                            ") at level " + std::to_string(key.level) + " of face " + std::to_string(key.face) +
                            (key.level < levels_ && window_ != 0 ? " in its window" : ""));
  return e;
}

bool PageTable::has_entry(const PageKey& key) const { return entry_at(key, window_centre_) != kNoEntry; }

// The page of the window (centred on `centre`) whose place modulo the window's size is
// the entry's.
PageKey PageTable::key_at(uint32_t entry, glm::uvec2 centre) const {
  if (entry >= entries()) throw std::out_of_range("page table: no entry " + std::to_string(entry));
  const uint32_t face = entry / face_entries_, local = entry % face_entries_;
  const uint32_t level = level_of(entry);
  const uint32_t grid = shared::page_table_grid(virtual_resolution_, page_size_, window_, level);
  const uint32_t index = local - level_first_[level];
  const glm::uvec2 place(index % grid, index / grid);
  const glm::uvec2 origin = shared::page_window_origin(virtual_resolution_, page_size_, window_, level, centre);
  return {level, origin + (place + grid - origin % grid) % grid, face};
}

PageKey PageTable::key(uint32_t entry) const { return key_at(entry, window_centre_); }

uint32_t PageTable::level_of(uint32_t entry) const {
  const uint32_t local = entry % face_entries_;
  return uint32_t(std::upper_bound(level_first_.begin(), level_first_.end(), local) - level_first_.begin()) - 1;
}

std::vector<uint32_t> PageTable::resident_entries() const {
  std::vector<uint32_t> resident;
  for (uint32_t owner : slot_owner_)
    if (owner != kNoSlot) resident.push_back(owner);
  std::sort(resident.begin(), resident.end());
  return resident;
}

uint32_t PageTable::move_window(glm::uvec2 centre) {
  if (centre == window_centre_) return 0;
  const glm::uvec2 before = window_centre_;
  // The windowed levels come first in each face's entries; the whole ones never move.
  const uint32_t windowed = level_first_[shared::page_window_levels(virtual_resolution_, page_size_, window_)];
  auto leaves = [&](uint32_t e) { return e % face_entries_ < windowed && entry_at(key_at(e, before), centre) != e; };
  // Only resident and requested pages hold state: the others' entries are as good as new.
  uint32_t left = 0;
  for (uint32_t e : resident_entries()) {
    if (!leaves(e)) continue;
    free_slots_.push_back(pages_[e].slot);
    release(e);
    pages_[e] = Page{};
    ++left;
  }
  std::erase_if(requested_, [&](uint32_t e) {
    if (!leaves(e)) return false;
    pages_[e] = Page{};
    return true;
  });
  left_window_since_plan_ += left;
  window_centre_ = centre;
  ++revision_;
  return left;
}

std::vector<std::vector<uint32_t>> PageTable::requests_in_window(std::span<const std::span<const uint32_t>> faces,
                                                                 glm::uvec2 centre) const {
  std::vector<std::vector<uint32_t>> moved(faces.size(), std::vector<uint32_t>((face_entries_ + 31) / 32, 0u));
  for (uint32_t f = 0; f < faces.size() && f < faces_; ++f)
    for_each_set_bit(faces[f], face_entries_, [&](uint32_t local) {
      const uint32_t now = entry_at(key_at(f * face_entries_ + local, centre), window_centre_);
      if (now != kNoEntry) moved[f][(now % face_entries_) / 32] |= 1u << (now % face_entries_ % 32);
    });
  return moved;
}

std::vector<uint32_t> PageTable::face_table_words(uint32_t face) const {
  const auto first = table_.begin() + ptrdiff_t(face) * face_entries_;
  return {first, first + face_entries_};
}

void PageTable::add_requests(std::span<const std::span<const uint32_t>> faces, glm::uvec2 centre) {
  if (centre != window_centre_) {  // marked before the windows moved: as entries of today's
    const std::vector<std::vector<uint32_t>> moved = requests_in_window(faces, centre);
    const std::vector<std::span<const uint32_t>> spans(moved.begin(), moved.end());
    add_requests(spans, window_centre_);
    return;
  }
  ++request_clock_;
  for (uint32_t e : requested_) pages_[e].requested = false;
  requested_.clear();
  auto ask = [&](uint32_t e) {
    Page& page = pages_[e];
    if (page.requested) return;
    page.requested = true;
    page.last_request = request_clock_;
    requested_.push_back(e);
  };
  for (uint32_t f = 0; f < faces.size() && f < faces_; ++f)
    for_each_set_bit(faces[f], face_entries_, [&](uint32_t local) { ask(f * face_entries_ + local); });
  if (required_level_ < levels_)
    for (uint32_t f = 0; f < faces_; ++f)
      for (uint32_t local = level_first_[required_level_]; local < level_first_[required_level_ + 1]; ++local)
        ask(f * face_entries_ + local);
  std::sort(requested_.begin(), requested_.end());
  stats_.requested = uint32_t(requested_.size());
  adapt_lod_bias();
}

void PageTable::require_level(uint32_t level) {
  if (level >= levels_) throw std::out_of_range("page table: no level " + std::to_string(level));
  required_level_ = level;
  add_requests(std::span<const std::span<const uint32_t>>());
}

bool PageTable::has_pending_requests() const {
  for (uint32_t e : requested_)
    if (needs_build(e)) return true;
  for (uint32_t face = 0; face < faces_; ++face)
    if (needs_build(root(face))) return true;
  return false;
}

bool PageTable::overflowed_lately(float bias) const {
  constexpr uint64_t kLately = 16;  // frames: a swing, if any, is one move in this many
  const auto seen = seen_at_bias_.find(int(std::lround(bias / kBiasStep)));
  return seen != seen_at_bias_.end() && request_clock_ - seen->second.clock <= kLately &&
         float(seen->second.requested) > kPoolHigh * float(slots_);
}

void PageTable::adapt_lod_bias() {
  const float share = float(stats_.requested) / float(slots_);
  seen_at_bias_[int(std::lround(lod_bias_ / kBiasStep))] = {stats_.requested, request_clock_};
  const float before = lod_bias_;
  // Requests fall about 4x per level (2x per side), so the bias that brings them to
  // kPoolTarget is log4 of the excess: one frame's move, in whole quarter steps,
  // rather than a step a frame (each of which would rebuild the pages it
  // moves, and keep a capture waiting).
  if (share > kPoolHigh) {
    const float quarters = std::ceil(std::log(share / kPoolTarget) / std::log(4.0f) / kBiasStep) * kBiasStep;
    lod_bias_ = std::min(lod_bias_ + std::max(kBiasStep, quarters), float(fallback_level_));
  } else if (stats_.unserved > 0) {
    lod_bias_ = std::min(lod_bias_ + kBiasStep, float(fallback_level_));
  } else if (share < kPoolLow) {
    // Down by as many steps as the worst growth keeps under kPoolHigh (one step when
    // nothing asked: every receiver read the coarsest level), but not to a bias whose
    // requests overflowed lately: a pool too small for any bias to land its requests
    // between kPoolLow and kPoolHigh would swing between two.
    const float steps = share > 0.0f ? std::max(1.0f, std::floor(std::log(kPoolHigh / share) / std::log(kGrowthPerStep))) : 1.0f;
    float lower = std::max(lod_bias_ - steps * kBiasStep, 0.0f);
    while (lower < lod_bias_ && overflowed_lately(lower)) lower += kBiasStep;
    lod_bias_ = std::min(lower, lod_bias_);
  }
  stats_.settling = lod_bias_ != before;
}

bool PageTable::needs_build(uint32_t entry) const {
  const Page& page = pages_[entry];
  return (page.requested || is_root(entry)) && (page.slot == kNoSlot || !page.current);
}

void PageTable::assign(uint32_t entry, uint32_t slot) {
  pages_[entry].slot = slot;
  slot_owner_[slot] = entry;
  table_[entry] = slot + 1;
  ++revision_;
}

void PageTable::release(uint32_t entry) {
  Page& page = pages_[entry];
  slot_owner_[page.slot] = kNoSlot;
  page.slot = kNoSlot;
  page.current = false;
  table_[entry] = shared::kPageAbsent;
  ++revision_;
}

std::vector<PageBuild> PageTable::plan_builds(uint32_t budget) {
  PageStats stats;
  stats.slots = slots_;
  stats.requested = stats_.requested;
  stats.settling = stats_.settling;
  stats.invalidated = invalidated_since_plan_;
  invalidated_since_plan_ = 0;
  stats.evicted = left_window_since_plan_;
  left_window_since_plan_ = 0;
  // Wanted: coarsest level first, every face's (within a face its entries come last), so
  // the stand-ins for missing fine pages improve first.
  // Only requested pages and the roots may need a build; ties go to the later entry.
  std::vector<uint32_t> wanted;
  for (uint32_t e : requested_)
    if (needs_build(e)) wanted.push_back(e);
  for (uint32_t face = 0; face < faces_; ++face)
    if (!pages_[root(face)].requested && needs_build(root(face))) wanted.push_back(root(face));
  std::sort(wanted.begin(), wanted.end(), [&](uint32_t a, uint32_t b) {
    const uint32_t level_a = level_of(a), level_b = level_of(b);
    return level_a != level_b ? level_a > level_b : a > b;
  });
  // Slots to take back, least recently requested first: resident pages nobody asked for
  // in the last frame, of any face (never a face's root).
  std::vector<uint32_t> evictable;
  for (uint32_t e : resident_entries())
    if (!pages_[e].requested && !is_root(e)) evictable.push_back(e);
  std::stable_sort(evictable.begin(), evictable.end(),
                   [&](uint32_t a, uint32_t b) { return pages_[a].last_request < pages_[b].last_request; });
  size_t next_evictable = 0;

  std::vector<PageBuild> builds;
  for (uint32_t e : wanted) {
    if (budget != 0 && builds.size() >= budget) break;
    if (pages_[e].slot == kNoSlot) {
      if (free_slots_.empty() && next_evictable < evictable.size()) {
        const uint32_t victim = evictable[next_evictable++];
        free_slots_.push_back(pages_[victim].slot);
        release(victim);
        ++stats.evicted;
      }
      if (free_slots_.empty()) {
        ++stats.unserved;
        continue;
      }
      assign(e, free_slots_.back());
      free_slots_.pop_back();
    }
    pages_[e].current = true;  // built by this frame, before its lookups
    builds.push_back({e, key(e), pages_[e].slot});
  }
  stats.resident = uint32_t(slots_ - free_slots_.size());  // a slot is free or held
  for (uint32_t e : requested_)
    if (pages_[e].slot == kNoSlot || !pages_[e].current) ++stats.pending;
  stats.built = uint32_t(builds.size());
  if (!builds.empty()) ++revision_;  // pages rebuilt in their slots change the map, not the table
  stats.lod_bias = lod_bias_;
  stats_ = stats;
  return builds;
}

// A stale page gives its slot up at once, so no lookup reads it: coarser pages serve
// until it is built again. The root keeps its slot; it is the first page rebuilt.
void PageTable::invalidate(uint32_t entry) {
  Page& page = pages_.at(entry);
  if (page.slot == kNoSlot) return;
  ++invalidated_since_plan_;
  page.current = false;
  if (is_root(entry)) return;
  free_slots_.push_back(page.slot);
  release(entry);
}

void PageTable::invalidate_all() {
  for (uint32_t e : resident_entries()) invalidate(e);  // the others have nothing to lose
}

uint32_t PageTable::invalidate_overlapping(std::span<const UvRect> rects, uint32_t face) {
  uint32_t count = 0;
  for (uint32_t e : resident_entries()) {
    if (e / face_entries_ != face) continue;
    const UvRect page = window(key(e), 1.0f);
    if (std::none_of(rects.begin(), rects.end(), [&](const UvRect& r) { return r.overlaps(page); })) continue;
    invalidate(e);
    ++count;
  }
  return count;
}

UvRect PageTable::window(const PageKey& key, float margin_texels) const {
  const float raster = float(std::max(virtual_resolution_ >> key.level, page_size_));
  const glm::vec2 first = glm::vec2(key.page * page_size_) - margin_texels;
  const glm::vec2 end = glm::vec2((key.page + 1u) * page_size_) + margin_texels;
  return {first / raster, end / raster};
}

}  // namespace avsm::passes
