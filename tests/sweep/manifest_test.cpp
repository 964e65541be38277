// Sweep manifests: the cross product and the explicit list expand to the jobs (ids,
// settings, avsm-capture arguments, references), and every mistake is an error naming
// the file and the JSON path inside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/load_error.h"
#include "sweep/manifest.h"

namespace avsm::sweep {
namespace manifest_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;

// A folder with the manifest's two scene files (only their existence is checked here).
class ManifestTest : public testing::Test {
 protected:
  void SetUp() override {
    // A folder per test: CTest runs this file's tests as parallel processes.
    dir_ = fs::path(testing::TempDir()) / (std::string("sweep_manifest_") + testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "scenes");
    std::ofstream(dir_ / "scenes" / "a.scene.json") << "{}";
    std::ofstream(dir_ / "scenes" / "b.scene.json") << "{}";
  }
  fs::path manifest_file() const { return dir_ / "m.json"; }
  std::string scene(const std::string& name) const { return (dir_ / "scenes" / name).lexically_normal().string(); }
  SweepIndex parse(const std::string& text) const { return parse_manifest(text, manifest_file()); }
  std::string error_of(const std::string& text) const {
    try {
      parse(text);
    } catch (const scene::LoadError& e) {
      return e.what();
    }
    return "(no error)";
  }

  fs::path dir_;
};

// Two scenes x one resolution x two shadow settings, compared against the exact one.
const char* kCross = R"({
  "version": 1,
  "defaults": { "frames": 1, "compare_to": "uncompressed", "shadow": { "resolution": 64 } },
  "cross": {
    "scenes": [ { "id": "a", "scene": "scenes/a.scene.json" },
                { "id": "b", "scene": "scenes/../scenes/b.scene.json", "camera": "side" } ],
    "resolutions": [ { "id": "tiny", "width": 96, "height": 54 } ],
    "shadows": [ { "id": "avsm4", "technique": "avsm", "nodes": 4, "filter": "point" },
                 { "id": "exact", "technique": "uncompressed" } ],
    "reference": { "shadows": "exact" }
  }
})";

TEST_F(ManifestTest, CrossProductExpandsInAxisOrder) {
  const SweepIndex index = parse(kCross);
  EXPECT_EQ(index.manifest, manifest_file().string());
  ASSERT_EQ(index.jobs.size(), 4u);
  const std::vector<std::string> ids = {"a-tiny-avsm4", "a-tiny-exact", "b-tiny-avsm4", "b-tiny-exact"};
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(index.jobs[i].id, ids[i]);
    EXPECT_EQ(index.jobs[i].output, ids[i]);
    EXPECT_EQ(index.jobs[i].status, JobStatus::pending);
  }
  const JobRecord& job = index.jobs[2];
  EXPECT_EQ(job.settings.scene, scene("b.scene.json"));  // relative to the manifest, normalized
  EXPECT_EQ(job.settings.camera, "side");
  EXPECT_EQ(job.settings.width, 96u);
  EXPECT_EQ(job.settings.height, 54u);
  EXPECT_EQ(job.settings.frames, 1u);
  EXPECT_EQ(job.settings.shadow.technique, "avsm");
  EXPECT_EQ(job.settings.shadow.nodes, 4);
  EXPECT_EQ(job.settings.shadow.resolution, 64);  // from the defaults
  EXPECT_EQ(job.settings.shadow.filter, scene::ShadowFilter::point);
  EXPECT_FALSE(job.settings.shadow.sort);
  EXPECT_EQ(job.settings.compare_to, "uncompressed");
  EXPECT_EQ(job.settings.reference_job, "b-tiny-exact");
  EXPECT_EQ(index.jobs[3].settings.reference_job, "");  // the reference itself
  EXPECT_EQ(job.capture_args,
            (std::vector<std::string>{"--scene", scene("b.scene.json"), "--camera", "side", "--width", "96", "--height",
                                      "54", "--frames", "1", "--technique", "avsm", "--nodes", "4", "--filter", "point",
                                      "--shadow-res", "64", "--compare-to", "uncompressed"}));
}

TEST_F(ManifestTest, ExplicitJobsFollowTheProductWithTheDefaults) {
  const SweepIndex index = parse(R"({
    "version": 1,
    "defaults": { "width": 160, "height": 90, "shadow": { "technique": "osm", "parameters": { "slices": 32 } } },
    "cross": { "shadows": [ { "id": "osm" }, { "id": "exact", "technique": "uncompressed" } ] },
    "jobs": [ { "id": "default-scene", "compare_to": "none", "reference_job": "exact",
                "shadow": { "parameters": { "depth_bias": 0.5 } } } ]
  })");
  ASSERT_EQ(index.jobs.size(), 3u);
  const JobRecord& job = index.jobs[2];
  EXPECT_EQ(job.id, "default-scene");
  EXPECT_EQ(job.settings.scene, "");  // avsm-capture's default scene
  EXPECT_EQ(job.settings.frames, capture::CaptureOptions{}.frames);
  EXPECT_EQ(job.settings.shadow.technique, "osm");
  EXPECT_EQ(job.settings.shadow.parameters, (std::map<std::string, double>{{"depth_bias", 0.5}, {"slices", 32}}));
  EXPECT_EQ(job.settings.reference_job, "exact");
  EXPECT_EQ(job.capture_args,
            (std::vector<std::string>{"--width", "160", "--height", "90", "--technique", "osm", "--shadow-param",
                                      "depth_bias=0.5", "--shadow-param", "slices=32"}));
}

// A shot split into chunks of 4 frames: one job each, "<id>.f<first>-<last>", the last
// chunk shorter; each a --frame-range of avsm-capture, all naming their shot.
TEST_F(ManifestTest, AShotSplitsIntoChunksOfFrames) {
  const SweepIndex index = parse(R"({
    "version": 1,
    "jobs": [ { "id": "orbit", "frame_range": "10:19", "fps": 30, "chunk": 4 },
              { "id": "whole", "frame_range": "0:2" } ]
  })");
  ASSERT_EQ(index.jobs.size(), 4u);
  EXPECT_EQ(index.jobs[0].id, "orbit.f0010-0013");
  EXPECT_EQ(index.jobs[1].id, "orbit.f0014-0017");
  EXPECT_EQ(index.jobs[2].id, "orbit.f0018-0019");
  EXPECT_EQ(index.jobs[3].id, "whole") << "without a chunk, the shot is one job under its own id";
  const JobSettings& last = index.jobs[2].settings;
  EXPECT_EQ(last.shot, "orbit");
  EXPECT_EQ(last.first_frame, 18);
  EXPECT_EQ(last.last_frame, 19);
  EXPECT_FLOAT_EQ(last.fps, 30.0f);
  EXPECT_EQ(index.jobs[2].capture_args, (std::vector<std::string>{"--frame-range", "18:19", "--fps", "30"}));
  EXPECT_EQ(index.jobs[3].settings.shot, "whole");
}

TEST_F(ManifestTest, ShotMistakesNameTheirPath) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"version": 1, "jobs": [ { "id": "a", "frame_range": "9:2" } ]})",
       "jobs[0].frame_range: expected \"A:B\" with 0 <= A <= B, got '9:2'"},
      {R"({"version": 1, "jobs": [ { "id": "a", "chunk": 4 } ]})", "jobs[0].chunk: splits a shot: give the job a \"frame_range\""},
      {R"({"version": 1, "jobs": [ { "id": "a", "frame_range": "0:4", "fps": -1 } ]})", "jobs[0].fps: must be a frame rate in (0, 1000]"}};
  for (const auto& [manifest, message] : cases) {
    const std::string error = error_of(manifest);
    EXPECT_NE(error.find(message), std::string::npos) << error;
  }
}

TEST_F(ManifestTest, CaptureOptionsCarryTheSettings) {
  const JobSettings settings = parse(kCross).jobs[0].settings;
  const capture::CaptureOptions options = capture_options(settings);
  EXPECT_EQ(options.scene, scene("a.scene.json"));
  EXPECT_EQ(options.shadow, settings.shadow);
  EXPECT_TRUE(options.compare_to_uncompressed);
  EXPECT_EQ(capture_options(JobSettings{}).scene, capture::CaptureOptions{}.scene);  // empty: the default scene
}

// Each mistake and the message part that must name it (all prefixed with the file).
TEST_F(ManifestTest, EveryErrorNamesItsPath) {
  const std::string job = R"({"version": 1, "jobs": [ {"id": "ok"}, )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {job + R"({"id": "x", "shadow": {"nodes": 7}} ]})", "jobs[1].shadow.nodes: must be 4, 8, 12 or 16, got 7"},
      {job + R"({"id": "x", "shadoww": {}} ]})", "jobs[1].shadoww: unknown key (did you mean 'shadow'?)"},
      {job + R"({"id": "x", "width": "wide"} ]})", "jobs[1].width: expected a whole number, got a string"},
      {job + R"({"id": "x", "width": 20000} ]})", "jobs[1].width: must be 1 to 16384, got 20000"},
      {job + R"({"id": "x", "frames": 0} ]})", "jobs[1].frames: must be 1 to 1000, got 0"},
      {job + R"({"id": "x", "shadow": {"technique": "bogus"}} ]})", "jobs[1].shadow.technique: 'bogus' is not one of avsm, "},
      {job + R"({"id": "x", "shadow": {"distance": 3}} ]})", "jobs[1].shadow.distance: unknown key"},
      {job + R"({"id": "ok"} ]})", "jobs[1].id: job id 'ok' is already the id of a job of jobs[0]"},
      {job + R"({"id": "a/b"} ]})", "jobs[1].id: 'a/b' is not a usable id"},
      {job + R"({"id": "slurm"} ]})", "jobs[1].id: 'slurm' is not a usable id"},
      {job + R"({"id": "x", "reference_job": "nope"} ]})", "jobs[1].reference_job: no job has the id 'nope'"},
      {job + R"({"id": "x", "reference_job": "x"} ]})", "jobs[1].reference_job: a job cannot be its own reference"},
      {job + R"({"id": "x", "width": 96, "height": 54, "reference_job": "ok"} ]})",
       "jobs[1].reference_job: 'ok' renders 1280x720, this job 96x54; images compare only at the same size"},
      {job + R"({"id": "x", "compare_to": "exact"} ]})", "jobs[1].compare_to: 'exact' is not one of uncompressed, none"},
      {job + R"({"id": "x", "scene": "missing.scene.json"} ]})", "jobs[1].scene: no such file '"},
      {job + R"({"id": "x", "shadow": {"cascades": 2, "clusters": 4}} ]})",
       "jobs[1]: avsm-capture refuses the settings of job 'x': --cascades and --clusters exclude each other"},
      {job + R"({"id": "x", "id": "y"} ]})", "jobs[1].id: duplicate key"},
      {R"({"version": 1, "cross": {"shadows": [ {"id": "a"}, {"id": "a", "nodes": 4} ]}})",
       "cross.shadows[1].id: 'a' is already the id of cross.shadows[0]"},
      {R"({"version": 1, "cross": {"shadows": [ {"id": "a", "scene": "x"} ]}})", "cross.shadows[0].scene: unknown key"},
      {R"({"version": 1, "cross": {"shadows": [ {"id": "a"} ], "reference": {"shadows": "b"}}})",
       "cross.reference.shadows: 'b' is not an id of cross.shadows (a)"},
      {R"({"version": 1, "cross": {"shadows": [ {"id": "a"} ], "reference": {"scenes": "a"}}})",
       "cross.reference.scenes: unknown key"},
      {R"({"version": 1, "cross": {"scenes": []}})", "cross.scenes: expected a non-empty array"},
      {R"({"version": 1, "cross": {}})", "cross: needs at least one of the axes"},
      {R"({"version": 1, "cross": {"shadows": [ {"id": "a-b"} ]}, "jobs": [ {"id": "a-b"} ]})",
       "jobs[0].id: job id 'a-b' is already the id of a job of cross"},
      {R"({"version": 1, "defaults": {"id": "x"}, "jobs": [ {"id": "a"} ]})", "defaults.id: unknown key"},
      {R"({"version": 2, "jobs": [ {"id": "a"} ]})", "version: unsupported version 2"},
      {R"({"version": 1})", "top level: the manifest lists no jobs"},
      {R"({"version": 1, "jobs": [ {"id": "a"} )", "invalid JSON"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = error_of(text);
    EXPECT_EQ(message.rfind(manifest_file().string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << message;
  }
}

TEST_F(ManifestTest, ReadsTheFileAndNamesIt) {
  std::ofstream(manifest_file()) << kCross;
  EXPECT_EQ(read_manifest(manifest_file()).jobs.size(), 4u);
  try {
    read_manifest(dir_ / "absent.json");
    FAIL() << "no error";
  } catch (const scene::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace manifest_test
}  // namespace avsm::sweep
