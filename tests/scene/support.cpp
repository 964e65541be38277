#include "support.h"

#include <cstring>
#include <fstream>
#include <unistd.h>

namespace avsm::scene::testing {

std::filesystem::path shared_content(const std::string& relative) {
  return std::filesystem::path(AVSM_SHARED_CONTENT_DIR).lexically_normal() / relative;
}
std::filesystem::path project_content(const std::string& relative) {
  return std::filesystem::path(AVSM_PROJECT_CONTENT_DIR) / relative;
}
std::filesystem::path default_content(const std::string& relative) {
  return std::filesystem::path(AVSM_DEFAULT_CONTENT_DIR) / relative;
}
std::filesystem::path assimp_model(const std::string& relative) {
  return std::filesystem::path(AVSM_ASSIMP_MODELS_DIR) / relative;
}

TempDir::TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "scene";
  path_ = std::filesystem::temp_directory_path() / ("avsm_scene_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::vector<std::byte> read_bytes(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::vector<char> chars((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  std::vector<std::byte> bytes(chars.size());
  if (!chars.empty()) std::memcpy(bytes.data(), chars.data(), chars.size());
  return bytes;
}

void write_bytes(const std::filesystem::path& file, const std::vector<std::byte>& bytes) {
  std::ofstream stream(file, std::ios::binary);
  stream.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  ASSERT_TRUE(stream.good()) << "cannot write " << file;
}

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream stream(file);
  stream << text;
  ASSERT_TRUE(stream.good()) << "cannot write " << file;
}

std::string load_error_of(const std::function<void()>& load) {
  try {
    load();
  } catch (const LoadError& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "expected a LoadError, got another exception: " << error.what();
    return {};
  }
  ADD_FAILURE() << "expected a LoadError, but loading succeeded";
  return {};
}

}  // namespace avsm::scene::testing
