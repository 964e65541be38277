#pragma once
// Golden files: tests/rendergraph/golden/<name>.txt, found through RG_GOLDEN_DIR (set by
// CMake to the absolute source path). RG_UPDATE_GOLDEN=1 rewrites them instead of
// comparing; review the diff before committing.
#include <gtest/gtest.h>

#include <string>

namespace rg_test {

::testing::AssertionResult matches_golden(const std::string& name, const std::string& actual);

// Line diff of two texts ("-" expected, "+" actual), with two lines of context.
std::string line_diff(const std::string& expected, const std::string& actual);

}  // namespace rg_test
