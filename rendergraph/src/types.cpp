#include <rendergraph/types.h>

#include "hash.h"

namespace rg {

const char* to_string(QueueType queue) {
  switch (queue) {
    case QueueType::Graphics: return "graphics";
    case QueueType::Compute: return "compute";
    case QueueType::Transfer: return "transfer";
  }
  return "?";
}

const char* to_string(ResourceKind kind) { return kind == ResourceKind::Texture ? "texture" : "buffer"; }

std::size_t hash_value(const TextureDesc& desc) {
  detail::Fnv1a hash;
  for (uint64_t field : {uint64_t{desc.width}, uint64_t{desc.height}, uint64_t{desc.depth},
                         uint64_t{desc.mip_levels}, uint64_t{desc.array_layers}, uint64_t(desc.format)})
    hash.add(field);
  return static_cast<std::size_t>(hash.value());
}

std::size_t hash_value(const BufferDesc& desc) {
  detail::Fnv1a hash;
  hash.add(desc.size);
  return static_cast<std::size_t>(hash.value());
}

}  // namespace rg
