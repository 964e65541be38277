// The Slurm side of sweeps without a cluster: the sbatch script, the --array value,
// slurm.json, and the hints for sbatch's refusals (messages as Slurm 22.05 prints
// them). The local cluster test (slurm_sweep_test.sh) submits for real.
#include "sweep/slurm.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace avsm::sweep {
namespace slurm_test {  // one per file: test targets are unity builds
namespace {

TEST(SlurmArraySpec, RunsOfConsecutiveTasksBecomeRanges) {
  EXPECT_EQ(array_spec({0, 1, 2, 3}), "0-3");
  EXPECT_EQ(array_spec({5}), "5");
  EXPECT_EQ(array_spec({7, 0, 2, 1, 5, 6, 2}), "0-2,5-7");
  EXPECT_EQ(array_spec({1, 3}), "1,3");
}

TEST(SlurmScript, RunsTheSweepTaskOfEachArrayIndex) {
  const std::string script = sbatch_script("/shared/sweeps/nightly", "/opt/avsm/bin/avsm-sweep", {0, 1, 2, 3}, {});
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("\n#SBATCH --array=0-3 "), std::string::npos);
  EXPECT_NE(script.find("\n#SBATCH --output=\"/shared/sweeps/nightly/slurm/task-%a.log\"\n"), std::string::npos);
  EXPECT_NE(script.find("\nexec '/opt/avsm/bin/avsm-sweep' task '/shared/sweeps/nightly' --index \"$SLURM_ARRAY_TASK_ID\"\n"),
            std::string::npos);
  // Requests not given are disabled examples for the admin, never active lines.
  EXPECT_NE(script.find("\n##SBATCH --partition=gpu "), std::string::npos);
  EXPECT_NE(script.find("\n##SBATCH --gres=gpu:1 "), std::string::npos);
  EXPECT_EQ(script.find("\n#SBATCH --partition"), std::string::npos);
  EXPECT_EQ(script.find("\n#SBATCH --gres"), std::string::npos);
  EXPECT_NE(script.find("storage every node mounts"), std::string::npos);
}

TEST(SlurmScript, OptionsBecomeSbatchLines) {
  SlurmOptions options;
  options.partition = "render";
  options.time = "01:00:00";
  options.mem = "16G";
  options.gres = "gpu:a100:1";
  options.sbatch_args = {"--account=lighting", "--qos=nightly"};
  const std::string script = sbatch_script("/shared/s", "/opt/avsm-sweep", {2, 4}, options);
  EXPECT_NE(script.find("\n#SBATCH --array=2,4 "), std::string::npos);
  for (const char* line : {"\n#SBATCH --partition=render ", "\n#SBATCH --time=01:00:00 ", "\n#SBATCH --mem=16G ",
                           "\n#SBATCH --gres=gpu:a100:1 ", "\n#SBATCH --account=lighting\n", "\n#SBATCH --qos=nightly\n"}) {
    EXPECT_NE(script.find(line), std::string::npos) << line;
  }
}

TEST(SlurmScript, QuotesPathsForTheShell) {
  const std::string script = sbatch_script("/shared/it's here", "/opt/avsm-sweep", {0}, {});
  EXPECT_NE(script.find("task '/shared/it'\\''s here' --index"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --chdir=\"/shared/it's here\"\n"), std::string::npos);
}

TEST(SlurmScript, RelativePathsAndEmptySweepsAreRefused) {
  EXPECT_THROW(sbatch_script("sweep", "/opt/avsm-sweep", {0}, {}), std::logic_error);
  EXPECT_THROW(sbatch_script("/shared/s", "/opt/avsm-sweep", {}, {}), std::runtime_error);
}

TEST(SlurmSubmissionJson, RoundTrips) {
  const SlurmSubmission submission{"4711", {0, 2, 3}, "/shared/s/slurm/sweep.sbatch"};
  EXPECT_EQ(slurm_submission_from_json(to_json(submission)), submission);
  nlohmann::json broken = to_json(submission);
  broken.erase("job_id");
  EXPECT_THROW(
      {
        try {
          slurm_submission_from_json(broken);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("job_id"), std::string::npos) << e.what();
          throw;
        }
      },
      std::runtime_error);
}

TEST(SbatchErrorHint, NamesTheSettingToChange) {
  EXPECT_NE(sbatch_error_hint("sbatch: error: invalid partition specified: nosuch").find("--partition"), std::string::npos);
  EXPECT_NE(sbatch_error_hint("sbatch: error: Invalid generic resource (gres) specification").find("--gres"),
            std::string::npos);
  EXPECT_NE(sbatch_error_hint("sbatch: error: Invalid --time specification").find("--time"), std::string::npos);
  EXPECT_NE(sbatch_error_hint("sbatch: error: Memory specification can not be satisfied sbatch: error: Batch job "
                              "submission failed: Requested node configuration is not available")
                .find("--mem"),
            std::string::npos);
  EXPECT_NE(sbatch_error_hint("sbatch: error: Batch job submission failed: Invalid job array specification")
                .find("MaxArraySize"),
            std::string::npos);
  EXPECT_NE(sbatch_error_hint("sbatch: error: Batch job submission failed: Unable to contact slurm controller "
                              "(connect failure)")
                .find("SLURM_CONF"),
            std::string::npos);
  EXPECT_EQ(sbatch_error_hint("sbatch: error: something new"), "");
}

TEST(SlurmStates, FinishedStatesAreNotActive) {
  for (const char* state : {"PENDING", "RUNNING", "COMPLETING", "CONFIGURING", "SUSPENDED", "REQUEUED"}) {
    EXPECT_TRUE(is_active_slurm_state(state)) << state;
  }
  for (const char* state : {"COMPLETED", "FAILED", "TIMEOUT", "CANCELLED", "NODE_FAIL", "OUT_OF_MEMORY"}) {
    EXPECT_FALSE(is_active_slurm_state(state)) << state;
  }
}

}  // namespace
}  // namespace slurm_test
}  // namespace avsm::sweep
