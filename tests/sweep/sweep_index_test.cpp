// The sweep's job index: index.json and job.json read back to what was written,
// collect() merges the per-job files, and a bad file's error names the file and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "sweep/sweep_index.h"

namespace avsm::sweep {
namespace sweep_index_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;

JobRecord sample_job(const std::string& id) {
  JobRecord job;
  job.id = id;
  job.settings.scene = "/scenes/a.scene.json";
  job.settings.camera = "close";
  job.settings.width = 96;
  job.settings.height = 54;
  job.settings.frames = 1;
  job.settings.shadow.technique = "avsm";
  job.settings.shadow.nodes = 8;
  job.settings.shadow.filter = scene::ShadowFilter::point;
  job.settings.shadow.build = scene::ShadowBuild::fixed;
  job.settings.shadow.sort = false;
  job.settings.shadow.virtual_lights = 64;
  job.settings.shadow.parameters["depth_bias"] = 0.25;
  job.settings.compare_to = "uncompressed";
  job.settings.reference_job = "a-exact";
  job.capture_args = {"--scene", "/scenes/a.scene.json", "--nodes", "8"};
  job.output = id;
  return job;
}

SweepIndex sample_index() {
  SweepIndex index;
  index.manifest = "/sweeps/m.json";
  index.jobs = {sample_job("a-avsm8"), sample_job("a-exact")};
  index.jobs[1].settings.shadow = {};
  index.jobs[1].settings.shadow.technique = "uncompressed";
  index.jobs[1].status = JobStatus::failed;
  index.jobs[1].exit_code = 1;
  index.jobs[1].error = "avsm-capture: error: x.scene.json: missing";
  index.jobs[1].wall_s = 2.5;
  return index;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("sweep_index_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepIndex, JsonRoundTrip) {
  const SweepIndex index = sample_index();
  EXPECT_EQ(sweep_index_from_json(to_json(index)), index);
  // Only the overrides set are written; unset ones stay unset.
  const nlohmann::json exact = to_json(index.jobs[1].settings.shadow);
  EXPECT_EQ(exact, nlohmann::json({{"technique", "uncompressed"}}));
  EXPECT_TRUE(to_json(index.jobs[0]).at("exit_code").is_null());
}

TEST(SweepIndex, FilesRoundTripAndCollectMergesJobFiles) {
  const fs::path dir = fresh_dir("collect");
  SweepIndex index = sample_index();
  write_index(dir, index);
  EXPECT_EQ(read_index(dir), index);
  EXPECT_FALSE(read_job_record(dir, "a-avsm8"));

  JobRecord done = index.jobs[0];
  done.status = JobStatus::done;
  done.exit_code = 0;
  done.wall_s = 1.5;
  write_job_record(dir, done);
  EXPECT_EQ(read_job_record(dir, "a-avsm8"), done);
  for (const auto& entry : fs::directory_iterator(dir / "a-avsm8"))  // the temporary file was renamed
    EXPECT_EQ(entry.path().filename(), "job.json");

  const SweepIndex collected = collect(dir);
  EXPECT_EQ(collected.jobs[0], done);
  EXPECT_EQ(collected.jobs[1], index.jobs[1]);  // no job.json: as prepared
  EXPECT_EQ(read_index(dir), collected);
}

TEST(SweepIndex, MissingKeyIsNamedWithTheFile) {
  const fs::path dir = fresh_dir("missing_key");
  nlohmann::json broken = to_json(sample_index());
  broken["jobs"][1]["settings"].erase("height");
  std::ofstream(dir / "index.json") << broken.dump();
  const std::string message = error_of([&] { read_index(dir); });
  EXPECT_NE(message.find("index.json: jobs[1]: settings: no \"height\""), std::string::npos) << message;
}

TEST(SweepIndex, BadValuesAreNamed) {
  nlohmann::json job = to_json(sample_job("x"));
  job["status"] = "finished";
  EXPECT_NE(error_of([&] { job_record_from_json(job); }).find("\"status\": unknown value 'finished'"), std::string::npos);
  job = to_json(sample_job("x"));
  job["settings"]["shadow"]["filter"] = "cubic";
  EXPECT_NE(error_of([&] { job_record_from_json(job); }).find("settings: shadow: \"filter\": unknown value 'cubic'"),
            std::string::npos);
  job = to_json(sample_job("x"));
  job["output"] = "..";
  EXPECT_NE(error_of([&] { job_record_from_json(job); }).find("\"output\": '..' is not a job folder"), std::string::npos);
  job = to_json(sample_job("../x"));
  EXPECT_NE(error_of([&] { job_record_from_json(job); }).find("not a job id"), std::string::npos);
}

TEST(SweepIndex, JobFileOfAnotherJobIsAnError) {
  const fs::path dir = fresh_dir("wrong_folder");
  write_job_record(dir, sample_job("a"));
  fs::create_directories(dir / "b");
  fs::copy_file(dir / "a" / "job.json", dir / "b" / "job.json");
  const std::string message = error_of([&] { read_job_record(dir, "b"); });
  EXPECT_NE(message.find("holds job 'a', not 'b'"), std::string::npos) << message;
}

TEST(SweepIndex, JobIds) {
  EXPECT_TRUE(is_valid_job_id("default-avsm8_1.5"));
  for (const char* bad : {"", ".", "..", "a/b", "a b", "é", "slurm", "index.json"}) EXPECT_FALSE(is_valid_job_id(bad)) << bad;
}

}  // namespace
}  // namespace sweep_index_test
}  // namespace avsm::sweep
