// avsm/shadows.h needs no rendergraph/ header: this file is compiled with a poisoned
// copy of every rendergraph header ahead of the real ones (tests/api/CMakeLists.txt),
// each an #error naming itself, so a public header that reaches one fails the build.
#include <avsm/shadows.h>

int main() {
  // The pass list's types are complete here, as a host without the frame graph uses them.
  avsm::ShadowPassList list;
  list.passes.push_back({"a pass", avsm::PassQueue::compute, {}, false, {}});
  return list.passes.size() == 1 && list.lookup.records == avsm::kNoPassResource ? 0 : 1;
}
