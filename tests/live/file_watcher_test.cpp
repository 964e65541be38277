// FileWatcher on real files with time driven by the test: changes are handed out
// once settled, a vanished file is waited for, and a read that overlapped a write
// is not confirmed. No GPU.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "live/file_watcher.h"

namespace avsm::live {
namespace file_watcher_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;
using std::chrono::milliseconds;

constexpr SettleTimes kTimes{milliseconds(150), milliseconds(2000)};

class FileWatcherTest : public testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("avsm_watch_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    write(a(), "first");
    write(b(), "other");
    watcher_.watch({a(), b()});
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path a() const { return root_ / "a.txt"; }
  fs::path b() const { return root_ / "b.txt"; }
  // Editors' writes: a different length, so the change shows within one time stamp tick.
  static void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::trunc) << text; }
  std::vector<fs::path> after(milliseconds elapsed) { return watcher_.settled_changes(now_ += elapsed); }

  fs::path root_;
  FileWatcher watcher_{kTimes};
  Clock::time_point now_ = Clock::time_point{} + std::chrono::hours(1);
};

TEST_F(FileWatcherTest, ChangeIsHandedOutOnceItHeldStillForTheSettleTime) {
  EXPECT_TRUE(after(milliseconds(0)).empty());
  EXPECT_FALSE(watcher_.busy());
  write(a(), "second!");
  EXPECT_TRUE(after(milliseconds(0)).empty());  // just seen
  EXPECT_TRUE(watcher_.busy());
  EXPECT_TRUE(after(milliseconds(149)).empty());
  EXPECT_EQ(after(milliseconds(1)), std::vector<fs::path>{a()});
  EXPECT_TRUE(watcher_.confirm(now_));
  EXPECT_FALSE(watcher_.busy());
  EXPECT_TRUE(after(milliseconds(500)).empty());  // read: not handed out again
}

TEST_F(FileWatcherTest, SavesInQuickSuccessionAreHandedOutOnceAfterTheLast) {
  write(a(), "0");
  after(milliseconds(0));
  for (int save = 1; save <= 10; ++save) {
    write(a(), std::string(size_t(save) + 1, 'x'));
    EXPECT_TRUE(after(milliseconds(5)).empty()) << "save " << save;
  }
  EXPECT_TRUE(after(milliseconds(149)).empty());  // 150 ms after the first save, not the last
  EXPECT_EQ(after(milliseconds(1)), std::vector<fs::path>{a()});
}

TEST_F(FileWatcherTest, EveryChangedFileSettlesBeforeAnyIsHandedOut) {
  write(a(), "model.gltf, new");
  after(milliseconds(0));
  write(b(), "model.bin, new!");
  EXPECT_TRUE(after(milliseconds(150)).empty());  // a settled, b did not yet
  EXPECT_EQ(after(milliseconds(150)), (std::vector<fs::path>{a(), b()}));
}

TEST_F(FileWatcherTest, VanishedFileIsWaitedForThenHandedOutWhenRecreatedOrAfterTheGrace) {
  fs::remove(a());
  EXPECT_TRUE(after(milliseconds(0)).empty());
  EXPECT_TRUE(after(milliseconds(1000)).empty());  // settled, but missing: being saved
  EXPECT_TRUE(watcher_.busy());
  write(a(), "recreated");
  EXPECT_TRUE(after(milliseconds(0)).empty());  // the new file settles afresh
  EXPECT_TRUE(after(milliseconds(149)).empty());
  EXPECT_EQ(after(milliseconds(1)), std::vector<fs::path>{a()});
  EXPECT_TRUE(watcher_.confirm(now_));

  // Gone for good: handed out after the grace, so that reading it reports it missing.
  fs::remove(a());
  EXPECT_TRUE(after(milliseconds(0)).empty());
  EXPECT_TRUE(after(milliseconds(1999)).empty());
  EXPECT_EQ(after(milliseconds(1)), std::vector<fs::path>{a()});
  EXPECT_TRUE(watcher_.confirm(now_));
  EXPECT_TRUE(after(milliseconds(5000)).empty());  // reported once
}

TEST_F(FileWatcherTest, ReadThatOverlappedAWriteIsNotConfirmed) {
  write(a(), "half");
  after(milliseconds(0));
  ASSERT_EQ(after(milliseconds(150)), std::vector<fs::path>{a()});
  write(a(), "half, then the rest");  // lands while the caller reads
  EXPECT_FALSE(watcher_.confirm(now_));
  EXPECT_TRUE(watcher_.busy());
  EXPECT_TRUE(after(milliseconds(149)).empty());
  EXPECT_EQ(after(milliseconds(1)), std::vector<fs::path>{a()});  // again, once settled
  EXPECT_TRUE(watcher_.confirm(now_));
}

TEST_F(FileWatcherTest, ReadWhileAnotherChangeSettlesIsNotConfirmed) {
  // A read for another reason (a new scene file asked for) while b is being written.
  write(b(), "being written");
  after(milliseconds(0));
  EXPECT_FALSE(watcher_.confirm(now_ += milliseconds(10)));
  EXPECT_EQ(after(milliseconds(150)), std::vector<fs::path>{b()});
}

TEST_F(FileWatcherTest, ZeroSettleTimeHandsOutAtOnce) {
  FileWatcher at_once({milliseconds(0), milliseconds(0)});
  at_once.watch({a()});
  write(a(), "whole file");
  EXPECT_EQ(at_once.settled_changes(now_), std::vector<fs::path>{a()});
  EXPECT_TRUE(at_once.confirm(now_));
  fs::remove(a());
  EXPECT_EQ(at_once.settled_changes(now_), std::vector<fs::path>{a()});
}

TEST_F(FileWatcherTest, WatchKeepsTheStateOfFilesWatchedAlready) {
  write(a(), "pending change");
  after(milliseconds(0));
  const fs::path c = root_ / "c.txt";
  write(c, "new asset");
  watcher_.watch({a(), c});  // b dropped, c added as read
  EXPECT_EQ(watcher_.files(), (std::vector<fs::path>{a(), c}));
  EXPECT_EQ(after(milliseconds(150)), std::vector<fs::path>{a()});
}

}  // namespace
}  // namespace file_watcher_test
}  // namespace avsm::live
