// CompiledPlan::to_json: the same content as to_text, for tools (flags as symbolic strings).
#include <cstdio>
#include <sstream>

#include "plan_format.h"

namespace rg {
namespace {

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string index_or_null(uint32_t index) { return index == kInvalidIndex ? "null" : std::to_string(index); }

// null for a whole resource, else {"offset":..,"size":..}.
std::string range_json(const BufferRange& range) {
  if (range.whole()) return "null";
  return "{\"offset\":" + std::to_string(range.offset) + ",\"size\":" + std::to_string(range.size) + "}";
}

std::string barrier_json(const Barrier& b) {
  std::ostringstream out;
  out << "{\"resource\":" << index_or_null(b.resource) << ",\"range\":" << range_json(b.range) << ",\"src_stages\":" << json_string(stage_names(b.src_stages))
      << ",\"src_access\":" << json_string(access_names(b.src_access))
      << ",\"dst_stages\":" << json_string(stage_names(b.dst_stages))
      << ",\"dst_access\":" << json_string(access_names(b.dst_access))
      << ",\"old_layout\":" << json_string(layout_name(b.old_layout))
      << ",\"new_layout\":" << json_string(layout_name(b.new_layout)) << ",\"aliased\":[";
  for (size_t i = 0; i < b.aliased.size(); ++i) out << (i ? "," : "") << b.aliased[i];
  out << "]}";
  return out.str();
}

std::string access_json(const PlannedAccess& a) {
  std::ostringstream out;
  out << "{\"resource\":" << a.resource << ",\"range\":" << range_json(a.range) << ",\"usages\":" << json_string(detail::usage_names(a.usages))
      << ",\"reads\":" << (a.reads ? "true" : "false") << ",\"writes\":" << (a.writes ? "true" : "false")
      << ",\"read_version\":" << a.read_version << ",\"written_version\":" << a.written_version
      << ",\"stages\":" << json_string(stage_names(a.stages)) << ",\"access\":" << json_string(access_names(a.access))
      << ",\"layout\":" << json_string(layout_name(a.layout)) << "}";
  return out.str();
}

template <class T, class Fn>
std::string json_array(const std::vector<T>& items, Fn&& to_json) {
  std::string out = "[";
  for (size_t i = 0; i < items.size(); ++i) {
    if (i) out += ',';
    out += to_json(items[i]);
  }
  return out + "]";
}

std::string pass_json(const PlannedPass& pass) {
  return detail::cat("{\"name\":", json_string(pass.name), ",\"queue\":", json_string(to_string(pass.queue)),
                     ",\"pass_index\":", std::to_string(pass.pass_index),
                     ",\"barriers\":", json_array(pass.barriers, barrier_json),
                     ",\"accesses\":", json_array(pass.accesses, access_json), "}");
}

std::string state_json(const ImportState& state) {
  return detail::cat("{\"stages\":", json_string(stage_names(state.stages)),
                     ",\"access\":", json_string(access_names(state.access)),
                     ",\"layout\":", json_string(layout_name(state.layout)), "}");
}

std::string resource_json(const PlannedResource& r) {
  std::ostringstream out;
  out << "{\"name\":" << json_string(r.name) << ",\"kind\":" << json_string(to_string(r.kind))
      << ",\"desc\":" << json_string(detail::desc_text(r)) << ",\"imported\":" << (r.imported ? "true" : "false");
  if (r.imported) out << ",\"initial\":" << state_json(r.initial) << ",\"final\":" << state_json(r.final_state);
  out << ",\"used\":" << (r.used ? "true" : "false") << ",\"first_pass\":" << index_or_null(r.first_pass)
      << ",\"last_pass\":" << index_or_null(r.last_pass) << ",\"usages\":" << json_string(detail::usage_names(r.usages))
      << ",\"heap\":" << index_or_null(r.heap) << ",\"offset\":" << r.offset << ",\"size\":" << r.size << "}";
  return out.str();
}

std::string heap_json(const PlannedHeap& heap) {
  std::ostringstream out;
  out << "{\"memory_type_bits\":" << heap.memory_type_bits << ",\"size\":" << heap.size
      << ",\"alignment\":" << heap.alignment << ",\"resources\":[";
  for (size_t i = 0; i < heap.resources.size(); ++i) out << (i ? "," : "") << heap.resources[i];
  out << "]}";
  return out.str();
}

}  // namespace

std::string CompiledPlan::to_json() const {
  std::ostringstream out;
  out << "{\"options\":{\"aliasing\":" << (options.aliasing ? "true" : "false")
      << ",\"culling\":" << (options.culling ? "true" : "false")
      << ",\"serial_full_barriers\":" << (options.serial_full_barriers ? "true" : "false") << "}"
      << ",\"shape_hash\":\"" << std::hex << shape_hash << std::dec << "\""
      << ",\"passes\":" << json_array(passes, pass_json)
      << ",\"final_barriers\":" << json_array(final_barriers, barrier_json)
      << ",\"culled_passes\":" << json_array(culled_passes, pass_json)
      << ",\"resources\":" << json_array(resources, resource_json) << ",\"heaps\":" << json_array(heaps, heap_json)
      << ",\"stats\":{\"transient_bytes_aliased\":" << stats.transient_bytes_aliased
      << ",\"transient_bytes_unaliased\":" << stats.transient_bytes_unaliased
      << ",\"barrier_count\":" << stats.barrier_count << "}}";
  return out.str();
}

}  // namespace rg
