#include "gpu/struct_layout.h"

#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace avsm::gpu {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, std::unique_ptr<StructLayout>> layouts;
};
Registry& registry() {
  static Registry instance;
  return instance;
}

bool same_layout(const StructLayout& a, const StructLayout& b) {
  if (a.size != b.size || a.members.size() != b.members.size()) return false;
  for (size_t i = 0; i < a.members.size(); ++i)
    if (std::strcmp(a.members[i].name, b.members[i].name) != 0 || a.members[i].offset != b.members[i].offset ||
        a.members[i].size != b.members[i].size)
      return false;
  return true;
}

}  // namespace

const StructLayout& register_struct_layout(const StructLayout& layout) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  auto [it, inserted] = r.layouts.try_emplace(layout.name, nullptr);
  if (inserted) {
    it->second = std::make_unique<StructLayout>(layout);
  } else if (!same_layout(*it->second, layout)) {
    throw std::logic_error(std::string("GPU struct '") + layout.name + "' is declared twice, differently (" +
                           it->second->declared_in + ", " + layout.declared_in + ")");
  }
  return *it->second;
}

const StructLayout* find_struct_layout(const std::string& name) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  auto it = r.layouts.find(name);
  return it == r.layouts.end() ? nullptr : it->second.get();
}

}  // namespace avsm::gpu
