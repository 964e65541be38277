#include "scene/load_error.h"

#include <utility>

namespace avsm::scene {

LoadError::LoadError(std::filesystem::path file, std::string problem)
    : std::runtime_error(file.string() + ": " + problem),
      file_(std::move(file)),
      problem_(std::move(problem)) {}

}  // namespace avsm::scene
