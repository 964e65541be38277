#pragma once
// FNV-1a, 64-bit: a stable hash (same value on every run and platform), unlike std::hash.
#include <cstdint>
#include <string_view>

namespace rg::detail {

class Fnv1a {
 public:
  void add_bytes(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      state_ ^= bytes[i];
      state_ *= 0x100000001b3ull;
    }
  }
  void add(uint64_t value) { add_bytes(&value, sizeof value); }
  void add(std::string_view text) {
    add(text.size());  // length first, so ("ab","c") and ("a","bc") differ
    add_bytes(text.data(), text.size());
  }
  uint64_t value() const { return state_; }

 private:
  uint64_t state_ = 0xcbf29ce484222325ull;
};

}  // namespace rg::detail
