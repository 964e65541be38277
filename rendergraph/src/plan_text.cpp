// CompiledPlan::to_text: the deterministic dump the golden tests compare against. One
// line per barrier, access, resource and heap; flags and layouts printed by name.
#include <sstream>

#include "plan_format.h"

namespace rg {
namespace {

std::string quoted(const CompiledPlan& plan, uint32_t resource) { return detail::cat("'", plan.resources[resource].name, "'"); }

// Buffer ranges as " [offset, end)"; nothing for whole resources (the common case).
std::string range_text(const BufferRange& range) {
  if (range.whole()) return "";
  return detail::cat(" [", std::to_string(range.offset), ", ", std::to_string(range.offset + range.size), ")");
}

std::string barrier_line(const CompiledPlan& plan, const Barrier& b) {
  std::string line = "barrier ";
  line += b.is_global() ? "(global)" : quoted(plan, b.resource);
  line += range_text(b.range);
  if (!b.is_global() && plan.resources[b.resource].kind == ResourceKind::Texture) {
    line += detail::cat(" layout ", layout_name(b.old_layout));
    if (b.new_layout != b.old_layout) line += detail::cat(" -> ", layout_name(b.new_layout));
    line += ",";
  }
  line += detail::cat(" src ", stage_names(b.src_stages), "/", access_names(b.src_access));
  line += detail::cat(", dst ", stage_names(b.dst_stages), "/", access_names(b.dst_access));
  for (size_t i = 0; i < b.aliased.size(); ++i) line += detail::cat(i == 0 ? ", aliases " : " ", quoted(plan, b.aliased[i]));
  return line;
}

std::string access_line(const CompiledPlan& plan, const PlannedAccess& a) {
  std::string line = a.reads && a.writes ? "read_write " : a.writes ? "write " : "read ";
  line += quoted(plan, a.resource);
  line += range_text(a.range);
  if (a.reads) line += detail::cat(" @", std::to_string(a.read_version));
  if (a.writes) line += detail::cat(" ->@", std::to_string(a.written_version));
  line += detail::cat(" ", detail::usage_names(a.usages));
  return line;
}

std::string pass_header(const PlannedPass& pass) {
  return detail::cat("'", pass.name, "' ", to_string(pass.queue), " (declared #", std::to_string(pass.pass_index), ")");
}

std::string resource_line(const PlannedResource& r) {
  std::string line = detail::cat("'", r.name, "' ", to_string(r.kind), " ", detail::desc_text(r));
  if (r.imported)
    line += detail::cat(", imported from ", detail::state_text(r.initial, r.kind), " to ",
                        detail::state_text(r.final_state, r.kind));
  if (!r.used) return line + ", unused";
  line += detail::cat(", passes ", std::to_string(r.first_pass), "..", std::to_string(r.last_pass));
  line += detail::cat(", usages ", detail::usage_names(r.usages));
  if (r.heap != kInvalidIndex)
    line += detail::cat(", heap ", std::to_string(r.heap), " offset ", std::to_string(r.offset), " size ",
                        std::to_string(r.size));
  return line;
}

const char* on_off(bool value) { return value ? "on" : "off"; }

}  // namespace

std::string CompiledPlan::to_text() const {
  std::ostringstream out;
  out << "options: aliasing " << on_off(options.aliasing) << ", culling " << on_off(options.culling)
      << ", serial barriers " << on_off(options.serial_full_barriers) << "\n";

  out << "passes:\n";
  for (size_t i = 0; i < passes.size(); ++i) {
    out << "  " << i << " " << pass_header(passes[i]) << "\n";
    for (const Barrier& b : passes[i].barriers) out << "      " << barrier_line(*this, b) << "\n";
    for (const PlannedAccess& a : passes[i].accesses) out << "    " << access_line(*this, a) << "\n";
  }
  out << "final barriers:\n";
  for (const Barrier& b : final_barriers) out << "      " << barrier_line(*this, b) << "\n";
  out << "culled passes:\n";
  for (const PlannedPass& pass : culled_passes) out << "  " << pass_header(pass) << "\n";

  out << "resources:\n";
  for (const PlannedResource& r : resources) out << "  " << resource_line(r) << "\n";
  out << "heaps:\n";
  for (size_t i = 0; i < heaps.size(); ++i) {
    const PlannedHeap& heap = heaps[i];
    out << "  " << i << ": memory_type_bits 0x" << std::hex << heap.memory_type_bits << std::dec << ", size "
        << heap.size << ", alignment " << heap.alignment << ", residents";
    for (uint32_t r : heap.resources) out << " " << quoted(*this, r);
    out << "\n";
  }
  out << "transient bytes: " << stats.transient_bytes_aliased << " with aliasing, " << stats.transient_bytes_unaliased
      << " without; barriers: " << stats.barrier_count << "\n";
  return out.str();
}

}  // namespace rg
