#pragma once
// Helpers for the scene tests: data locations, temporary folders, and checks
// on LoadError messages.
#include "scene/load_error.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace avsm::scene::testing {

std::filesystem::path shared_content(const std::string& relative);   // ../shared/content/<relative>
std::filesystem::path project_content(const std::string& relative);  // content/<relative>
std::filesystem::path default_content(const std::string& relative);  // build/content/default/<relative>
std::filesystem::path assimp_model(const std::string& relative);     // Debian assimp-testmodels

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

std::vector<std::byte> read_bytes(const std::filesystem::path& file);
void write_bytes(const std::filesystem::path& file, const std::vector<std::byte>& bytes);
void write_text(const std::filesystem::path& file, const std::string& text);

template <class T>
void put(std::vector<std::byte>& bytes, std::size_t offset, const T& value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}

// Runs `load` and returns the LoadError message; records a failure if it
// throws anything else or nothing.
std::string load_error_of(const std::function<void()>& load);

}  // namespace avsm::scene::testing

// Fails the test (not skips) when real data is missing: these tests exist to run on it.
#define AVSM_REQUIRE_FILE(path)                                                                       \
  ASSERT_TRUE(std::filesystem::exists(path))                                                          \
      << "missing test data " << (path)                                                               \
      << "\nThe real-asset tests need ../shared/content next to the project (see its README.md) and " \
         "Debian's assimp-testmodels package."

using ::testing::HasSubstr;
using ::testing::AllOf;
using ::testing::StartsWith;
