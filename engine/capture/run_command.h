#pragma once
// Runs a program found on PATH and collects what it prints: Slurm's commands for the
// sweeps, ffmpeg for a shot's video.
#include <optional>
#include <string>
#include <vector>

namespace avsm::capture {

struct CommandResult {
  int exit_code = -1;  // 128 + signal when killed by one
  std::string out;
  std::string err;
};

// Runs `args` (args[0] looked up on PATH) and collects its stdout and stderr.
// nullopt when the program is not installed; throws std::runtime_error when it cannot start.
std::optional<CommandResult> run_command(const std::vector<std::string>& args);

}  // namespace avsm::capture
