#include "capture/pass_list_json.h"

#include <nlohmann/json.hpp>
#include <rendergraph/vk_names.h>

#include <utility>
#include <vector>

#include "capture/files.h"

namespace avsm::capture {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order a reader expects them

// Names of the set bits of `flags` from `names`, joined by '|' ("NONE" for none).
std::string flag_names(uint32_t flags, const std::vector<std::pair<uint32_t, const char*>>& names) {
  std::string text;
  for (const auto& [bit, name] : names)
    if (flags & bit) {
      if (!text.empty()) text += '|';
      text += name;
    }
  return text.empty() ? "NONE" : text;
}

std::string image_usage_names(VkImageUsageFlags usage) {
  return flag_names(usage, {{VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "TRANSFER_SRC"},
                            {VK_IMAGE_USAGE_TRANSFER_DST_BIT, "TRANSFER_DST"},
                            {VK_IMAGE_USAGE_SAMPLED_BIT, "SAMPLED"},
                            {VK_IMAGE_USAGE_STORAGE_BIT, "STORAGE"},
                            {VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "COLOR_ATTACHMENT"},
                            {VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "DEPTH_STENCIL_ATTACHMENT"}});
}

std::string buffer_usage_names(VkBufferUsageFlags usage) {
  return flag_names(usage, {{VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "TRANSFER_SRC"},
                            {VK_BUFFER_USAGE_TRANSFER_DST_BIT, "TRANSFER_DST"},
                            {VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, "UNIFORM_TEXEL_BUFFER"},
                            {VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, "UNIFORM_BUFFER"},
                            {VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "STORAGE_BUFFER"},
                            {VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "INDEX_BUFFER"},
                            {VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "VERTEX_BUFFER"},
                            {VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, "INDIRECT_BUFFER"}});
}

Json state_json(const passes::PassResourceState& state, bool image) {
  Json json{{"stages", rg::stage_names(state.stages)}, {"access", rg::access_names(state.access)}};
  if (image) json["layout"] = rg::layout_name(state.layout);
  return json;
}

Json resource_json(const passes::PassResource& r) {
  const bool image = r.kind == passes::PassResource::Kind::image;
  Json json{{"name", r.name}, {"kind", image ? "image" : "buffer"}, {"transient", r.transient}};
  if (image) {
    json["width"] = r.image.width;
    json["height"] = r.image.height;
    json["depth"] = r.image.depth;
    json["mip_levels"] = r.image.mip_levels;
    json["array_layers"] = r.image.array_layers;
    json["format"] = rg::format_name(r.image.format);
    json["usage"] = image_usage_names(r.image.usage);
  } else {
    json["size"] = r.buffer.size;
    json["usage"] = buffer_usage_names(r.buffer.usage);
  }
  if (!r.sized_by.empty()) json["sized_by"] = r.sized_by;
  if (!r.transient) {
    json["initial"] = state_json(r.initial, image);
    json["final"] = state_json(r.final_state, image);
  }
  return json;
}

Json use_json(const passes::PassResourceUse& use, const passes::ShadowPassList& list) {
  const passes::PassResource& r = list.resources.at(use.resource);
  Json json{{"resource", r.name}, {"reads", use.reads}, {"writes", use.writes}, {"usages", use.usages},
            {"stages", rg::stage_names(use.stages)}, {"access", rg::access_names(use.access)}};
  if (r.kind == passes::PassResource::Kind::image) json["layout"] = rg::layout_name(use.layout);
  if (use.offset != 0 || use.size != VK_WHOLE_SIZE) {
    json["offset"] = use.offset;
    json["size"] = use.size;
  }
  return json;
}

Json names_of(const std::vector<uint32_t>& indices, const passes::ShadowPassList& list) {
  Json names = Json::array();
  for (uint32_t i : indices) names.push_back(list.resources.at(i).name);
  return names;
}

}  // namespace

std::string pass_list_json(const passes::ShadowPassList& list) {
  Json resources = Json::array(), passes = Json::array();
  for (const passes::PassResource& r : list.resources) resources.push_back(resource_json(r));
  for (const passes::ShadowPass& pass : list.passes) {
    Json uses = Json::array();
    for (const passes::PassResourceUse& use : pass.uses) uses.push_back(use_json(use, list));
    Json json{{"name", pass.name}, {"queue", passes::to_string(pass.queue)}, {"uses", uses}};
    if (pass.side_effect) json["side_effect"] = true;
    passes.push_back(json);
  }
  const passes::ShadowLookupResources& lookup = list.lookup;
  Json lookup_json{{"records", lookup.records == passes::kNoPassResource ? Json(nullptr)
                                                                          : Json(list.resources.at(lookup.records).name)},
                   {"maps", names_of(lookup.maps, list)},
                   {"lists", names_of(lookup.lists, list)}};
  Json json{{"version", 1}, {"resources", resources}, {"passes", passes}, {"lookup", lookup_json}};
  return json.dump(2) + "\n";
}

void write_pass_list(const std::filesystem::path& file, const passes::ShadowPassList& list) {
  write_text(file, pass_list_json(list));
}

}  // namespace avsm::capture
