#include "golden.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace rg_test {
namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

std::string line_diff(const std::string& expected, const std::string& actual) {
  const auto a = split_lines(expected), b = split_lines(actual);
  // Longest common subsequence table, then walk it to emit ' ', '-', '+' lines.
  std::vector<std::vector<int>> lcs(a.size() + 1, std::vector<int>(b.size() + 1, 0));
  for (size_t i = a.size(); i-- > 0;)
    for (size_t j = b.size(); j-- > 0;)
      lcs[i][j] = a[i] == b[j] ? lcs[i + 1][j + 1] + 1 : std::max(lcs[i + 1][j], lcs[i][j + 1]);

  std::vector<std::string> lines;
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (i < a.size() && j < b.size() && a[i] == b[j]) {
      lines.push_back("  " + a[i++]);
      ++j;
    } else if (i < a.size() && (j == b.size() || lcs[i + 1][j] >= lcs[i][j + 1])) {
      lines.push_back("- " + a[i++]);
    } else {
      lines.push_back("+ " + b[j++]);
    }
  }

  std::string out;
  constexpr size_t kContext = 2;
  for (size_t k = 0; k < lines.size(); ++k) {
    bool near_change = false;
    for (size_t m = (k > kContext ? k - kContext : 0); m < std::min(lines.size(), k + kContext + 1); ++m)
      near_change |= lines[m][0] != ' ';
    if (near_change) out += lines[k] + "\n";
    else if (out.size() >= 4 && out.compare(out.size() - 4, 4, "...\n") != 0) out += "...\n";
  }
  return out;
}

::testing::AssertionResult matches_golden(const std::string& name, const std::string& actual) {
  const std::string path = std::string(RG_GOLDEN_DIR) + "/" + name + ".txt";
  const char* update = std::getenv("RG_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    std::ofstream(path, std::ios::binary) << actual;
    return ::testing::AssertionSuccess() << "updated " << path;
  }
  std::ifstream file(path, std::ios::binary);
  if (!file)
    return ::testing::AssertionFailure() << "missing golden file " << path << " (run with RG_UPDATE_GOLDEN=1)";
  std::stringstream expected;
  expected << file.rdbuf();
  if (expected.str() == actual) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "plan differs from " << path
                                       << " (- golden, + actual; RG_UPDATE_GOLDEN=1 rewrites it):\n"
                                       << line_diff(expected.str(), actual);
}

}  // namespace rg_test
