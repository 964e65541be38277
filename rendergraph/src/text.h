#pragma once
// cat("a", name, std::to_string(n)): string building by appending. Used instead of
// `"literal" + std::string&&`, which makes g++ 12 emit a false -Wrestrict warning.
#include <string>
#include <string_view>

namespace rg::detail {

template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string text;
  (text.append(std::string_view(parts)), ...);
  return text;
}

}  // namespace rg::detail
