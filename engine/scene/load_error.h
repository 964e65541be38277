#pragma once
// The one exception type every scene loader throws on bad input, so callers can
// print a single line that names the offending file and what is wrong with it.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace avsm::scene {

class LoadError : public std::runtime_error {
 public:
  // what() reads "<file>: <problem>".
  LoadError(std::filesystem::path file, std::string problem);

  const std::filesystem::path& file() const noexcept { return file_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::filesystem::path file_;
  std::string problem_;
};

}  // namespace avsm::scene
