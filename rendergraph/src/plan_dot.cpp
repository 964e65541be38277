// CompiledPlan::to_dot: Graphviz view of the plan. Passes are boxes (culled ones grey),
// resources are ellipses (imported ones double) labelled with their placement; reads
// are edges resource -> pass, writes pass -> resource.
#include <cstdio>
#include <sstream>

#include "plan_format.h"

namespace rg {
namespace {

std::string dot_label(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string size_text(uint64_t bytes) {
  char text[32];
  if (bytes >= 1024 * 1024) std::snprintf(text, sizeof text, "%.2f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  else if (bytes >= 1024) std::snprintf(text, sizeof text, "%.1f KiB", static_cast<double>(bytes) / 1024.0);
  else std::snprintf(text, sizeof text, "%llu B", static_cast<unsigned long long>(bytes));
  return text;
}

void write_pass(std::ostringstream& out, const PlannedPass& pass, bool culled) {
  out << "  p" << pass.pass_index << " [shape=box, label=" << dot_label(detail::cat(pass.name, "\n", to_string(pass.queue)));
  if (culled) out << ", style=\"filled,dashed\", fillcolor=\"#dddddd\", fontcolor=\"#888888\"";
  out << "];\n";
  for (const PlannedAccess& a : pass.accesses) {
    const std::string style = culled ? ", color=\"#bbbbbb\", fontcolor=\"#bbbbbb\"" : "";
    const std::string label = dot_label(detail::usage_names(a.usages));
    if (a.reads) out << "  r" << a.resource << " -> p" << pass.pass_index << " [label=" << label << style << "];\n";
    if (a.writes) out << "  p" << pass.pass_index << " -> r" << a.resource << " [label=" << label << style << "];\n";
  }
}

}  // namespace

std::string CompiledPlan::to_dot() const {
  std::ostringstream out;
  out << "digraph rendergraph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n"
      << "  edge [fontname=\"Helvetica\", fontsize=8];\n";
  for (uint32_t r = 0; r < resources.size(); ++r) {
    const PlannedResource& res = resources[r];
    std::string label = detail::cat(res.name, "\n", detail::desc_text(res));
    if (res.heap != kInvalidIndex)
      label += detail::cat("\nheap ", std::to_string(res.heap), " @ ", std::to_string(res.offset), " (", size_text(res.size), ")");
    else if (res.imported)
      label += "\nimported";
    out << "  r" << r << " [shape=ellipse, label=" << dot_label(label);
    if (res.imported) out << ", peripheries=2";
    if (!res.used) out << ", color=\"#bbbbbb\", fontcolor=\"#888888\"";
    out << "];\n";
  }
  for (const PlannedPass& pass : passes) write_pass(out, pass, false);
  for (const PlannedPass& pass : culled_passes) write_pass(out, pass, true);
  out << "}\n";
  return out.str();
}

}  // namespace rg
