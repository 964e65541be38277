// The paged maps' CPU page table (passes/shadows/pages/page_table.h): layout, requests,
// builds within a budget and a pool, eviction by least recent request, invalidation,
// and the level-of-detail bias under overflow. No GPU needed.
#include "passes/shadows/pages/page_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <vector>

#include "shared/pages.h"

namespace avsm::passes {
namespace page_table_test {

// Request bits asking for `entries`.
std::vector<uint32_t> requests(const PageTable& table, const std::vector<uint32_t>& entries) {
  std::vector<uint32_t> bits((table.entries() + 31) / 32, 0u);
  for (uint32_t e : entries) bits[e / 32] |= 1u << (e % 32);
  return bits;
}

std::vector<uint32_t> built_entries(const std::vector<PageBuild>& builds) {
  std::vector<uint32_t> entries;
  for (const PageBuild& b : builds) entries.push_back(b.entry);
  return entries;
}

TEST(PageTableTest, LevelsRunFromTheVirtualResolutionDownToOnePage) {
  const PageTable table(1024, 64, 8);
  EXPECT_EQ(table.levels(), 5u);  // 1024, 512, 256, 128, 64 texels
  EXPECT_EQ(table.entries(), 16u * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1);
  EXPECT_EQ(shared::page_table_entries(1024, 64, 0), table.entries());
  for (uint32_t e = 0; e < table.entries(); ++e) EXPECT_EQ(table.entry(table.key(e)), e);
  EXPECT_EQ(table.key(table.entries() - 1), (PageKey{4, {0, 0}}));
  EXPECT_EQ(table.entry({1, {3, 2}}), 256u + 2 * 8 + 3);
  EXPECT_THROW(table.entry({0, {16, 0}}), std::out_of_range);
  EXPECT_THROW(PageTable(1000, 64, 8), std::invalid_argument);
  EXPECT_THROW(PageTable(1024, 64, 0), std::invalid_argument);
}

// A clipmap (a directional light's map): 4096 texels in pages of 64 (a grid of 64) with
// windows of 16 pages, so levels 0 and 1 keep 16x16 pages around the camera and levels
// 2 (16x16 pages) to 6 are whole.
TEST(PageTableTest, ClipmapLevelsKeepAWindowAroundTheCamera) {
  PageTable table(4096, 64, 64, ~0u, 1, 16);
  EXPECT_EQ(table.levels(), 7u);
  EXPECT_EQ(table.entries(), 2u * 16 * 16 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1);
  EXPECT_EQ(shared::page_table_entries(4096, 64, 16), table.entries());
  EXPECT_TRUE(table.has_entry({0, {15, 15}}));
  EXPECT_FALSE(table.has_entry({0, {16, 0}}));  // the window starts at the map's corner
  EXPECT_THROW(table.entry({0, {16, 0}}), std::out_of_range);
  EXPECT_TRUE(table.has_entry({2, {15, 15}}));  // a whole level
  table.move_window({2048, 2048});              // level 0: page 32, a window from 24; level 1: page 16, from 8
  EXPECT_TRUE(table.has_entry({0, {24, 39}}));
  EXPECT_FALSE(table.has_entry({0, {23, 30}}));
  EXPECT_FALSE(table.has_entry({0, {30, 40}}));
  EXPECT_TRUE(table.has_entry({1, {8, 23}}));
  EXPECT_FALSE(table.has_entry({1, {24, 8}}));
  for (uint32_t e = 0; e < table.entries(); ++e) EXPECT_EQ(table.entry(table.key(e)), e);
  table.move_window({4095, 0});  // kept inside the level: the last 16 pages
  EXPECT_TRUE(table.has_entry({0, {63, 0}}));
  EXPECT_TRUE(table.has_entry({0, {48, 15}}));
  EXPECT_FALSE(table.has_entry({0, {47, 0}}));
  EXPECT_THROW(PageTable(4096, 64, 8, ~0u, 1, 12), std::invalid_argument);
}

// Pages that stay in the window keep their slot and entry as the camera moves; a page
// that leaves gives both up; requests marked before the move land on today's entries.
TEST(PageTableTest, AMovingWindowKeepsThePagesThatStayInIt) {
  PageTable table(4096, 64, 64, ~0u, 1, 16);
  table.move_window({2048, 2048});  // level 0: pages 24..39
  const PageKey left{0, {25, 25}}, stays{0, {38, 38}};
  const uint32_t stays_entry = table.entry(stays), left_entry = table.entry(left);
  table.add_requests(requests(table, {table.entry(left), stays_entry}));
  table.plan_builds(0);
  ASSERT_TRUE(table.resident(table.entry(left)));
  ASSERT_TRUE(table.resident(stays_entry));
  const glm::uvec2 marked_at = table.window_centre();
  const std::vector<uint32_t> marked = requests(table, {table.entry(left), stays_entry});

  EXPECT_EQ(table.move_window({2048 + 3 * 64, 2048}), 1u);  // pages 27..42: (25, 25) leaves
  EXPECT_FALSE(table.has_entry(left));
  EXPECT_EQ(table.entry(stays), stays_entry);  // toroidal: the same entry
  EXPECT_TRUE(table.resident(stays_entry));
  // The last frame's requests, marked under the old window: (25, 25) is outside now.
  table.add_requests(std::vector<std::span<const uint32_t>>{marked}, marked_at);
  EXPECT_EQ(table.stats().requested, 1u);
  const std::vector<PageBuild> builds = table.plan_builds(0);
  EXPECT_TRUE(builds.empty()) << "the page that stayed is current";
  EXPECT_EQ(table.stats().evicted, 1u);  // the page that left the window
  EXPECT_EQ(table.stats().resident, 2u);  // (38, 38) and the root
  // The entry (25, 25) held now stands for a page that came in: absent until asked for.
  EXPECT_EQ(table.entry({0, {41, 25}}), left_entry);
  EXPECT_FALSE(table.resident(left_entry));
}

TEST(PageTableTest, TheCoarsestPageIsBuiltFirstAndRequestedPagesCoarsestFirst) {
  PageTable table(256, 64, 8);  // levels: 4x4, 2x2, 1 pages
  const uint32_t root = table.entries() - 1;
  EXPECT_EQ(built_entries(table.plan_builds(0)), std::vector<uint32_t>{root});
  EXPECT_TRUE(table.resident(root));
  const uint32_t fine = table.entry({0, {1, 2}}), mid = table.entry({1, {0, 1}});
  table.add_requests(requests(table, {fine, mid, root}));
  const std::vector<PageBuild> builds = table.plan_builds(0);
  EXPECT_EQ(built_entries(builds), (std::vector<uint32_t>{mid, fine}));
  EXPECT_EQ(builds[1].key, (PageKey{0, {1, 2}}));
  EXPECT_EQ(table.table_words()[fine], builds[1].slot + 1);
  EXPECT_EQ(table.table_words()[table.entry({0, {0, 0}})], shared::kPageAbsent);
  EXPECT_TRUE(table.converged());
  EXPECT_EQ(table.stats().resident, 3u);
  EXPECT_EQ(table.stats().built, 2u);
  // Asked again: nothing to build, the slots stay.
  table.add_requests(requests(table, {fine, mid, root}));
  EXPECT_TRUE(table.plan_builds(0).empty());
  EXPECT_EQ(table.table_words()[fine], builds[1].slot + 1);
}

TEST(PageTableTest, ABudgetSpreadsBuildsOverFramesAndCountsWhatWaits) {
  PageTable table(256, 64, 32);
  table.plan_builds(0);
  std::vector<uint32_t> fine;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) fine.push_back(table.entry({0, {x, y}}));
  table.add_requests(requests(table, fine));
  EXPECT_EQ(table.plan_builds(5).size(), 5u);
  EXPECT_EQ(table.stats().pending, 11u);
  EXPECT_FALSE(table.converged());
  table.add_requests(requests(table, fine));
  EXPECT_EQ(table.plan_builds(0).size(), 11u);
  EXPECT_TRUE(table.converged());
}

TEST(PageTableTest, AFullPoolEvictsTheLeastRecentlyRequestedPages) {
  PageTable table(256, 64, 4);  // the root and three more
  table.plan_builds(0);
  const uint32_t a = table.entry({0, {0, 0}}), b = table.entry({0, {1, 0}}), c = table.entry({0, {2, 0}});
  const uint32_t d = table.entry({0, {3, 0}}), e = table.entry({0, {0, 1}});
  table.add_requests(requests(table, {a, b, c}));
  table.plan_builds(0);
  table.add_requests(requests(table, {b}));  // a and c last asked for one frame earlier
  table.plan_builds(0);
  table.add_requests(requests(table, {c}));  // now a is the least recently requested
  table.plan_builds(0);
  table.add_requests(requests(table, {d}));
  const std::vector<PageBuild> builds = table.plan_builds(0);
  ASSERT_EQ(builds.size(), 1u);
  EXPECT_EQ(table.stats().evicted, 1u);
  EXPECT_FALSE(table.resident(a));
  EXPECT_TRUE(table.resident(b) && table.resident(c) && table.resident(d));
  // More requests than slots: what does not fit is unserved, never the root evicted.
  table.add_requests(requests(table, {a, b, c, d, e}));
  table.plan_builds(0);
  EXPECT_EQ(table.stats().unserved, 2u);
  EXPECT_TRUE(table.resident(table.entries() - 1));
  EXPECT_FALSE(table.converged());
}

// A point light's six faces share one pool: every face keeps its root; a busy face takes
// the slots an idle one does not need, and the least recently requested page of any face
// gives its slot up; each face reads its own words, and its requests its own bits.
TEST(PageTableTest, FacesShareOnePoolAndEachKeepsItsRoot) {
  constexpr uint32_t kFaces = 6;
  PageTable table(256, 64, 10, ~0u, kFaces);  // per face: 4x4, 2x2 and 1 page (21 entries)
  ASSERT_EQ(table.face_entries(), 21u);
  ASSERT_EQ(table.entries(), 21u * kFaces);
  EXPECT_EQ(table.key(table.entry({1, {1, 0}, 4})), (PageKey{1, {1, 0}, 4}));
  EXPECT_EQ(table.plan_builds(0).size(), kFaces) << "every face's root first";
  const auto face_bits = [&](uint32_t face, const std::vector<PageKey>& keys) {
    std::vector<uint32_t> bits((table.face_entries() + 31) / 32, 0u);
    for (PageKey key : keys) {
      key.face = face;
      const uint32_t local = table.entry(key) - face * table.face_entries();
      bits[local / 32] |= 1u << (local % 32);
    }
    return bits;
  };
  // Face 2 asks for four pages, face 5 for two: six of the four free slots' worth.
  std::vector<std::vector<uint32_t>> bits(kFaces, face_bits(0, {}));
  bits[2] = face_bits(2, {{0, {0, 0}}, {0, {1, 0}}, {0, {0, 1}}, {0, {1, 1}}});
  bits[5] = face_bits(5, {{1, {0, 0}}, {1, {1, 0}}});
  const auto add = [&] {
    const std::vector<std::span<const uint32_t>> spans(bits.begin(), bits.end());
    table.add_requests(spans);
  };
  add();
  const std::vector<PageBuild> builds = table.plan_builds(0);
  EXPECT_EQ(builds.size(), 4u);
  EXPECT_EQ(table.stats().unserved, 2u);
  // Coarsest first, over the faces: face 5's level-1 pages before face 2's level-0 ones.
  ASSERT_GE(builds.size(), 2u);
  EXPECT_EQ(builds[0].key.face, 5u);
  EXPECT_EQ(builds[1].key.face, 5u);
  for (uint32_t face = 0; face < kFaces; ++face) EXPECT_TRUE(table.resident(table.entry({2, {0, 0}, face})));
  // Face 5 stops asking: face 2's pages take its slots, the roots stay.
  bits[5] = face_bits(5, {});
  add();
  table.plan_builds(0);
  EXPECT_EQ(table.stats().evicted, 2u);
  EXPECT_EQ(table.stats().resident, 10u);
  EXPECT_EQ(table.stats().pending, 0u);
  EXPECT_EQ(table.stats().unserved, 0u);
  for (const PageKey& key : {PageKey{0, {0, 0}, 2}, PageKey{0, {1, 1}, 2}}) EXPECT_TRUE(table.resident(table.entry(key)));
  EXPECT_FALSE(table.resident(table.entry({1, {0, 0}, 5})));
  // Each face's words are its own entries; slots are the pool's.
  const std::vector<uint32_t> face2 = table.face_table_words(2);
  ASSERT_EQ(face2.size(), table.face_entries());
  EXPECT_EQ(face2[table.entry({0, {1, 1}, 2}) - 2 * table.face_entries()], table.table_words()[table.entry({0, {1, 1}, 2})]);
  EXPECT_NE(face2[0], shared::kPageAbsent);
  // A change seen by one face invalidates that face's pages only.
  // Its level-0 page (0, 0) and its root.
  EXPECT_EQ(table.invalidate_overlapping(std::vector<UvRect>{{glm::vec2(0.0f), glm::vec2(0.1f)}}, 2), 2u);
  EXPECT_TRUE(table.resident(table.entry({2, {0, 0}, 3})));
}

TEST(PageTableTest, InvalidatedPagesLeaveTheTableAndAreBuiltAgainWhenAskedFor) {
  PageTable table(256, 64, 8);
  table.plan_builds(0);
  const uint32_t page = table.entry({0, {2, 2}}), root = table.entries() - 1;
  table.add_requests(requests(table, {page}));
  table.plan_builds(0);
  table.invalidate_all();
  EXPECT_EQ(table.table_words()[page], shared::kPageAbsent);
  EXPECT_NE(table.table_words()[root], shared::kPageAbsent);  // kept, rebuilt first
  table.add_requests(requests(table, {page}));
  EXPECT_EQ(built_entries(table.plan_builds(0)), (std::vector<uint32_t>{root, page}));
  EXPECT_EQ(table.stats().invalidated, 2u);
  EXPECT_TRUE(table.converged());
}

TEST(PageTableTest, TheLodBiasGrowsUnderOverflowAndShrinksWhenRequestsFitAgain) {
  PageTable table(1024, 64, 10);
  table.plan_builds(0);
  std::vector<uint32_t> many;
  for (uint32_t x = 0; x < 16; ++x) many.push_back(table.entry({0, {x, 0}}));
  table.add_requests(requests(table, many));
  table.plan_builds(0);
  EXPECT_GT(table.stats().unserved, 0u);
  // 16 pages asked of 10 slots: log4(1.6 / 0.7) = 0.6 levels, in one frame's step of
  // whole quarters.
  EXPECT_EQ(table.lod_bias(), 0.75f);
  const float raised = table.lod_bias();
  for (int frame = 0; frame < 40; ++frame) {
    table.add_requests(requests(table, {many[0]}));
    table.plan_builds(0);
  }
  EXPECT_LT(table.lod_bias(), raised);
  EXPECT_EQ(table.lod_bias(), 0.0f);
}

// A change inside a rectangle of the map invalidates exactly the resident pages whose
// windows (widened by a texel of their level) overlap it, at every level; the rest stay.
TEST(PageTableTest, AChangeInvalidatesTheResidentPagesItOverlapsAtEveryLevel) {
  PageTable table(256, 64, 32);  // levels of 4x4, 2x2 and 1 page
  EXPECT_EQ(table.window({0, {1, 2}}).min, glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(table.window({0, {1, 2}}).max, glm::vec2(0.5f, 0.75f));
  EXPECT_EQ(table.window({1, {0, 0}}, 2.0f).min, glm::vec2(-2.0f / 128.0f));
  std::vector<uint32_t> all(table.entries());
  for (uint32_t e = 0; e < table.entries(); ++e) all[e] = e;
  table.add_requests(requests(table, all));
  ASSERT_EQ(table.plan_builds(0).size(), table.entries());
  // Inside level-0 page (1, 1), more than a texel from its edges: that page, level 1's
  // (0, 0) and the root.
  const UvRect inside{glm::vec2(0.30f), glm::vec2(0.45f)};
  EXPECT_EQ(table.invalidate_overlapping(std::span(&inside, 1)), 3u);
  for (uint32_t e = 0; e < table.entries(); ++e) {
    const PageKey k = table.key(e);
    const bool hit = (k.level == 0 && k.page == glm::uvec2(1, 1)) || (k.level == 1 && k.page == glm::uvec2(0, 0)) ||
                     k.level == 2;
    EXPECT_EQ(table.resident(e), !hit || k.level == 2) << "level " << k.level << " page " << k.page.x << "," << k.page.y;
  }
  table.add_requests(requests(table, all));
  EXPECT_EQ(table.plan_builds(0).size(), 3u) << "the stale pages are built again";
  EXPECT_EQ(table.stats().invalidated, 3u);
  // Within a texel of level-0 page (1, 1)'s right edge: its neighbour (2, 1) too, and
  // level 1's (1, 0); an empty rectangle invalidates nothing.
  const UvRect edge{glm::vec2(0.49f, 0.30f), glm::vec2(0.498f, 0.31f)};
  EXPECT_EQ(table.invalidate_overlapping(std::span(&edge, 1)), 5u);
  const UvRect nothing;
  EXPECT_EQ(table.invalidate_overlapping(std::span(&nothing, 1)), 0u);
}

// The revision moves with every build and table change, and stays while a frame
// changes nothing (what lets the light pictures skip a converged map).
TEST(PageTableTest, TheRevisionMovesOnlyWhenTheMapChanges) {
  PageTable table(256, 64, 32);
  const uint32_t page = table.entry({0, {1, 1}});
  table.add_requests(requests(table, {page}));
  table.plan_builds(0);  // the root and the page
  const uint64_t built = table.revision();
  EXPECT_GT(built, 0u);
  table.add_requests(requests(table, {page}));
  EXPECT_TRUE(table.plan_builds(0).empty());
  EXPECT_EQ(table.revision(), built) << "nothing built, nothing moved";
  table.invalidate(page);
  EXPECT_GT(table.revision(), built) << "the page left the table";
  const uint64_t invalidated = table.revision();
  table.add_requests(requests(table, {page}));
  EXPECT_EQ(table.plan_builds(0).size(), 1u);
  EXPECT_GT(table.revision(), invalidated);
}

}  // namespace page_table_test
}  // namespace avsm::passes
