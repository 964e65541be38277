#pragma once
// The graph's basic vocabulary: queues, resource descriptions, typed handles and the
// one exception type. Vulkan enums/flags are used as plain types only; the core never
// calls Vulkan and never links libvulkan.
#include <vulkan/vulkan_core.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace rg {

// Defined by the Vulkan backend. The core only stores execute callbacks taking it.
class PassContext;

// Every error the graph reports (bad handle, bad declaration, impossible usage).
// Messages name the pass and the resource, so the log alone points at the culprit.
class GraphError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr uint32_t kInvalidIndex = ~0u;

enum class QueueType : uint8_t { Graphics, Compute, Transfer };
enum class ResourceKind : uint8_t { Texture, Buffer };

const char* to_string(QueueType queue);
const char* to_string(ResourceKind kind);

struct TextureDesc {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t depth = 1;
  uint32_t mip_levels = 1;
  uint32_t array_layers = 1;
  VkFormat format = VK_FORMAT_UNDEFINED;
  // The setting that sizes it ("the light's shadow.resolution (--shadow-res)"), which a
  // memory model names when the device cannot hold it. Not part of the graph's shape.
  std::string sized_by;

  bool operator==(const TextureDesc&) const = default;
};

struct BufferDesc {
  uint64_t size = 0;
  std::string sized_by;  // as TextureDesc::sized_by

  bool operator==(const BufferDesc&) const = default;
};

// A byte range [offset, offset + size) of a buffer that passes access with its own
// synchronisation state (e.g. one mip level of a map stored in one buffer). The default
// is the whole buffer; kWholeSize reaches to its end, like VK_WHOLE_SIZE.
inline constexpr uint64_t kWholeSize = ~uint64_t{0};

struct BufferRange {
  uint64_t offset = 0;
  uint64_t size = kWholeSize;

  bool whole() const { return offset == 0 && size == kWholeSize; }
  // One past the last byte, for a buffer of `buffer_size` bytes.
  uint64_t end(uint64_t buffer_size) const { return size == kWholeSize ? buffer_size : offset + size; }
  bool operator==(const BufferRange&) const = default;
};

std::size_t hash_value(const TextureDesc& desc);
std::size_t hash_value(const BufferDesc& desc);

// A reference to one version of one resource of one graph. Every write returns a new
// version; handles to older versions become stale (Filament-style), so a pass cannot
// accidentally read data that a later pass already overwrote.
template <ResourceKind Kind>
struct Handle {
  static constexpr ResourceKind kind = Kind;

  uint32_t index = kInvalidIndex;  // into Graph::resources()
  uint32_t version = 0;            // 0 = as created/imported; +1 per write
  uint32_t graph_id = 0;           // Graph::id() of the graph that issued it

  bool valid() const { return index != kInvalidIndex; }
  bool operator==(const Handle&) const = default;
};

using TextureHandle = Handle<ResourceKind::Texture>;
using BufferHandle = Handle<ResourceKind::Buffer>;

}  // namespace rg

template <>
struct std::hash<rg::TextureDesc> {
  std::size_t operator()(const rg::TextureDesc& desc) const noexcept { return rg::hash_value(desc); }
};

template <>
struct std::hash<rg::BufferDesc> {
  std::size_t operator()(const rg::BufferDesc& desc) const noexcept { return rg::hash_value(desc); }
};
