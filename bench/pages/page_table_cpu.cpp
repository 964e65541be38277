// bench_page_table_cpu: what a paged light's page table costs the CPU each frame, at
// the default scene's size (a 16384^2 virtual map in pages of 32^2: 349,525 entries;
// the sun's pool of 2,112 slots), for a camera that stands still (the same requests
// every frame: nothing to build once converged) and one that orbits (a band of
// requests that moves each frame: pages to build and evict). A frame's work is what
// ShadowMaps does with the table: add the requests read back, plan the builds (32 a
// frame, the default scene's budget), ask whether requests are pending, copy the table
// the frame's lookups read. Prints the median over the frames after the first ten.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "passes/shadows/pages/page_table.h"
#include "shared/pages.h"

namespace {

using avsm::passes::PageKey;
using avsm::passes::PageTable;

constexpr uint32_t kVirtual = 16384, kPage = 32, kSlots = 2112, kBudget = 32, kFrames = 60;

// Request bits for a square of `side` level-0 pages at `origin` and the pages of the
// coarser levels above it (what a surface in view asks for, roughly).
std::vector<uint32_t> band(const PageTable& table, glm::uvec2 origin, uint32_t side) {
  std::vector<uint32_t> bits((table.face_entries() + 31) / 32, 0u);
  for (uint32_t level = 0; level < table.levels(); ++level) {
    const uint32_t grid = avsm::shared::page_grid(kVirtual, kPage, level);
    const glm::uvec2 first = glm::min(origin >> level, glm::uvec2(grid - 1));
    const uint32_t extent = std::max(1u, side >> level);
    for (uint32_t y = first.y; y < std::min(grid, first.y + extent); ++y)
      for (uint32_t x = first.x; x < std::min(grid, first.x + extent); ++x) {
        const uint32_t e = table.entry(PageKey{level, {x, y}, 0});
        bits[e / 32] |= 1u << (e % 32);
      }
  }
  return bits;
}

double median_frame_ms(uint32_t side, uint32_t step) {
  PageTable table(kVirtual, kPage, kSlots);
  std::vector<double> times;
  for (uint32_t frame = 0; frame < kFrames; ++frame) {
    const std::vector<uint32_t> bits = band(table, glm::uvec2(64 + frame * step, 64), side);
    const auto start = std::chrono::steady_clock::now();
    table.add_requests(std::span<const uint32_t>(bits));
    const auto builds = table.plan_builds(kBudget);
    const bool pending = table.has_pending_requests();
    const std::vector<uint32_t> words = table.face_table_words(0);
    const auto end = std::chrono::steady_clock::now();
    if (builds.size() > kSlots || (pending && words.empty())) std::abort();  // keeps the work
    if (frame >= 10) times.push_back(std::chrono::duration<double, std::milli>(end - start).count());
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

}  // namespace

int main() {
  std::printf("| camera | level-0 pages asked | CPU per light per frame |\n|---|---|---|\n");
  for (const uint32_t side : {8u, 24u, 40u}) {
    std::printf("| still | %u | %.3f ms |\n", side * side, median_frame_ms(side, 0));
    std::printf("| orbit (a page a frame) | %u | %.3f ms |\n", side * side, median_frame_ms(side, 1));
  }
}
