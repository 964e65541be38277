// The passes' grouping into the stages of a shadowed frame (capture/pass_stages.h), by
// the names the passes give themselves.
#include "capture/pass_stages.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace avsm::capture {
namespace pass_stages_test {  // one per file: test targets are unity builds
namespace {

TEST(PassStages, EveryPassNameOfTheEngineHasItsStage) {
  const std::vector<std::pair<std::string, PassStage>> expected = {
      {"light 0 clear lists", PassStage::shadow_capture},
      {"light 0 capture opaque", PassStage::shadow_capture},
      {"light 0 cascade 2 capture hair", PassStage::shadow_capture},
      {"light 12 face 5 capture smoke", PassStage::shadow_capture},
      {"light 0 light depth", PassStage::shadow_capture},
      {"light 0 hair bins clear", PassStage::shadow_capture},
      {"light 0 hair bins scan", PassStage::shadow_capture},
      {"light 0 sort lists", PassStage::sort},
      {"light 1 cluster 3 sort lists", PassStage::sort},
      {"light 0 avsm resolve", PassStage::build},
      {"light 0 avsm fixed build", PassStage::build},
      {"light 0 osm build", PassStage::build},
      {"light 0 fom fixed build", PassStage::build},
      {"light 0 dsm clear", PassStage::build},
      {"light 0 dsm build 3", PassStage::build},
      {"light 0 avsm mips level 1", PassStage::mips},
      {"light 1 cluster 0 avsm mips level 5", PassStage::mips},
      {"opaque", PassStage::camera},
      {"hair", PassStage::camera},
      {"hair lighting", PassStage::camera},
      {"volumes", PassStage::camera},
      {"volume march", PassStage::camera},
      {"volume composite", PassStage::camera},
      {"volume lighting cache", PassStage::camera},
      {"volume cache layout", PassStage::camera},
      {"light 0 copy lists", PassStage::other},
      {"light 3 debug image", PassStage::other},
      {"shadow parameters", PassStage::other},
      {"shadow quality", PassStage::other},
      {"shadow quality hair", PassStage::other},
      {"shadow probes", PassStage::other},
      {"shadow texel curves", PassStage::other},
      {"tonemap", PassStage::other},
      {"lighting", PassStage::other},  // not "light <index> ..."
  };
  for (const auto& [name, stage] : expected)
    EXPECT_EQ(to_string(pass_stage(name)), to_string(stage)) << "pass '" << name << "'";
}

// Finer than stages, for timings.json's per-frame shadow_step_gpu_ms: the capture split by
// caster kind, pages included.
TEST(PassStages, ShadowStepsSplitTheCaptureByCasterKind) {
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"light 0 page 7/1,1 capture opaque", "capture opaque"},
      {"light 0 page 5/3,4 capture hair", "capture hair"},
      {"light 12 face 5 page 2/0,0 capture smoke", "capture smoke"},
      {"light 1 capture opaque", "capture opaque"},
      {"light 0 page 7/1,1 clear lists", "shadow capture"},
      {"light 1 page 6/2,2 sort lists", "sort"},
      {"light 0 page 6/0,1 avsm resolve", "resolve / build"},
      {"light 0 avsm mips level 1", "mips"},
      {"opaque", ""},
      {"shadow probes", ""},
  };
  for (const auto& [name, step] : expected) EXPECT_EQ(shadow_step(name), step) << "pass '" << name << "'";
}

TEST(PassStages, StageTimesSumTheirPassesMedians) {
  TimingReport timings;
  auto pass = [](std::string name, double median) {
    PassTiming p;
    p.name = std::move(name);
    p.gpu_ms = {median / 2, median, median * 2};
    return p;
  };
  timings.passes = {pass("light 0 clear lists", 0.5),
                    pass("light 0 capture opaque", 1.0),
                    pass("light 0 sort lists", 2.0),
                    pass("light 0 avsm resolve", 4.0),
                    pass("light 0 avsm mips level 1", 8.0),
                    pass("opaque", 16.0),
                    pass("hair", 32.0),
                    pass("tonemap", 64.0)};
  const StageTimes stages = stage_gpu_ms(timings);
  EXPECT_DOUBLE_EQ(stages[size_t(PassStage::shadow_capture)], 1.5);
  EXPECT_DOUBLE_EQ(stages[size_t(PassStage::sort)], 2.0);
  EXPECT_DOUBLE_EQ(stages[size_t(PassStage::build)], 4.0);
  EXPECT_DOUBLE_EQ(stages[size_t(PassStage::mips)], 8.0);
  EXPECT_DOUBLE_EQ(stages[size_t(PassStage::camera)], 48.0);
  EXPECT_DOUBLE_EQ(stages[size_t(PassStage::other)], 64.0);
  EXPECT_DOUBLE_EQ(shadow_gpu_ms(stages), 15.5);
}

}  // namespace
}  // namespace pass_stages_test
}  // namespace avsm::capture
