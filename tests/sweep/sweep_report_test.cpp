// The sweep report's reading of a sweep folder (sweep/sweep_report.h) on a folder made
// here from typed reports: per-stage times, errors against uncompressed and against the
// reference job's frame, failed and unreadable jobs kept with their reasons; and the
// page shows them. CPU only (report.html in Chromium: tests/cmake/check_sweep_report.cmake).
#include "sweep/sweep_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "capture/files.h"
#include "io/image_io.h"

namespace avsm::sweep {
namespace sweep_report_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;

capture::TimingReport timings() {
  capture::TimingReport t;
  t.width = 4;
  t.height = 2;
  for (const auto& [name, ms] : {std::pair<const char*, double>{"light 0 capture opaque", 1.0},
                                 {"light 0 sort lists", 2.0},
                                 {"light 0 avsm resolve", 4.0},
                                 {"opaque", 8.0},
                                 {"shadow quality", 16.0}}) {
    capture::PassTiming pass;
    pass.name = name;
    pass.gpu_ms = {ms, ms, ms};
    t.passes.push_back(pass);
  }
  t.frame_gpu_ms = {31.0, 31.0, 31.0};
  return t;
}

capture::QualityReport quality(const std::string& technique, int nodes, capture::ErrorStats surface,
                               capture::ErrorStats smoke) {
  capture::LightQuality light;
  light.light = "sun";
  light.settings.technique = technique;
  light.settings.nodes = nodes;
  light.surface = surface;
  light.smoke = smoke;
  return {4, 2, {light}};
}

// A capture folder as avsm-capture writes it, frame.exr every channel at `value`.
void write_capture(const fs::path& dir, float value, const std::optional<capture::QualityReport>& q) {
  fs::create_directories(dir);
  capture::write_json(dir / "timings.json", capture::to_json(timings()));
  capture::MemoryReport memory;
  memory.transient_bytes_aliased = 4096;
  memory.lights.push_back({});
  memory.lights.back().map_bytes = 65536;
  capture::write_json(dir / "memory.json", capture::to_json(memory));
  if (q) capture::write_json(dir / "quality.json", capture::to_json(*q));
  const gpu::ImageRGBA32F image{4, 2, std::vector<float>(4 * 2 * 4, value)};
  io::write_exr(dir / "frame.exr", image);
  io::write_png_srgb(dir / "frame.png", image);
}

JobRecord job(const std::string& id, const std::string& technique, JobStatus status, const std::string& reference) {
  JobRecord j;
  j.id = id;
  j.output = id;
  j.status = status;
  j.exit_code = status == JobStatus::failed ? 3 : 0;
  j.settings.width = 4;
  j.settings.height = 2;
  j.settings.frames = 1;
  j.settings.shadow.technique = technique;
  j.settings.reference_job = reference;
  return j;
}

class SweepReport : public testing::Test {
 protected:
  void SetUp() override {
    // A folder per test: CTest runs this file's tests as parallel processes.
    dir_ = fs::path(testing::TempDir()) / (std::string("sweep_report_") + testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    write_capture(dir_ / "exact", 0.5f, quality("uncompressed", 8, {10, 0.0, 0.0}, {}));
    write_capture(dir_ / "avsm4", 0.75f, quality("avsm", 4, {100, 2.0, 0.1}, {50, 1.0, 0.3}));
    write_capture(dir_ / "lost", 0.5f, std::nullopt);
    fs::remove(dir_ / "lost" / "timings.json");
    write_capture(dir_ / "orphan", 0.5f, std::nullopt);
    index_.manifest = "/sweeps/m.json";
    index_.jobs = {job("exact", "uncompressed", JobStatus::done, ""), job("avsm4", "avsm", JobStatus::done, "exact"),
                   job("broken", "osm", JobStatus::failed, "exact"), job("lost", "avsm", JobStatus::done, ""),
                   job("orphan", "avsm", JobStatus::done, "broken")};
    index_.jobs[1].settings.shadow.nodes = 4;
    index_.jobs[2].error = "avsm-capture: <boom> & more";
    write_index(dir_, index_);
  }
  fs::path dir_;
  SweepIndex index_;
};

TEST_F(SweepReport, JobsReadWithTheirFiguresAndReasons) {
  const std::vector<JobResult> results = read_job_results(dir_, index_);
  ASSERT_EQ(results.size(), 5u);

  const JobResult& avsm4 = results[1];
  ASSERT_TRUE(avsm4.frame);
  EXPECT_EQ(avsm4.technique, "AVSM-4");
  EXPECT_DOUBLE_EQ(avsm4.stage_ms[size_t(capture::PassStage::shadow_capture)], 1.0);
  EXPECT_DOUBLE_EQ(capture::shadow_gpu_ms(avsm4.stage_ms), 7.0);
  EXPECT_DOUBLE_EQ(avsm4.stage_ms[size_t(capture::PassStage::camera)], 8.0);
  ASSERT_TRUE(avsm4.shadow_error);
  EXPECT_EQ(avsm4.shadow_error->receivers, 150u);  // surface and smoke together
  EXPECT_DOUBLE_EQ(avsm4.shadow_error->mean(), 3.0 / 150);
  EXPECT_DOUBLE_EQ(avsm4.shadow_error->max, 0.3);
  ASSERT_TRUE(avsm4.image_error) << avsm4.image_error_problem;
  EXPECT_NEAR(avsm4.image_error->mean_abs_error, 0.75 / 1.75 - 0.5 / 1.5, 1e-6);  // x / (1 + x) of 0.75 against 0.5

  EXPECT_EQ(results[0].technique, "uncompressed");
  EXPECT_FALSE(results[0].image_error);  // no reference job
  EXPECT_TRUE(results[0].image_error_problem.empty());

  EXPECT_FALSE(results[2].frame);  // failed: nothing read
  EXPECT_EQ(results[2].technique, "OSM-32");

  EXPECT_FALSE(results[3].frame);
  EXPECT_NE(results[3].problem.find("timings.json"), std::string::npos) << results[3].problem;

  ASSERT_TRUE(results[4].frame);
  EXPECT_FALSE(results[4].shadow_error);
  EXPECT_NE(results[4].image_error_problem.find("reference job 'broken'"), std::string::npos)
      << results[4].image_error_problem;
}

TEST_F(SweepReport, PageShowsEveryJobAndTheFailedJobsError) {
  write_sweep_report(dir_, dir_ / "report.html");
  std::ifstream in(dir_ / "report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const JobRecord& j : index_.jobs)
    EXPECT_NE(html.find("data-job=\"" + j.id + "\"><td"), std::string::npos) << "row of " << j.id;
  EXPECT_NE(html.find("avsm-capture: &lt;boom&gt; &amp; more"), std::string::npos);
  EXPECT_NE(html.find("<circle class=\"point\" data-job=\"avsm4\""), std::string::npos);
  EXPECT_EQ(html.find("<circle class=\"point\" data-job=\"orphan\""), std::string::npos);  // no quality.json
  EXPECT_NE(html.find("<img class=\"frame-image\" data-job=\"orphan\""), std::string::npos);
  EXPECT_NE(html.find("lost/timings.json"), std::string::npos);  // the unreadable job's reason
}

TEST_F(SweepReport, AnUnreadableIndexIsNamed) {
  capture::write_text(dir_ / "index.json", "{\"jobs\": 3}");
  try {
    write_sweep_report(dir_, dir_ / "report.html");
    FAIL() << "a broken index.json was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("index.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sweep_report_test
}  // namespace avsm::sweep
