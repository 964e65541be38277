#include "gpu/resources.h"

#include <cstring>
#include <stdexcept>
#include <utility>

#include "gpu/context.h"
#include "gpu/device_limits.h"
#include "gpu/vk_check.h"

namespace avsm::gpu {

// Preferred property sets per location, best first.
static uint32_t choose_memory_type(const Context& ctx, uint32_t type_bits, MemoryLocation location) {
  constexpr VkMemoryPropertyFlags kDevice = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  constexpr VkMemoryPropertyFlags kHost = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  std::vector<VkMemoryPropertyFlags> preferences;
  switch (location) {
    case MemoryLocation::DeviceLocal: preferences = {kDevice, 0}; break;
    case MemoryLocation::HostUpload: preferences = {kHost | kDevice, kHost}; break;
    case MemoryLocation::HostReadback: preferences = {kHost | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, kHost}; break;
  }
  for (VkMemoryPropertyFlags flags : preferences) {
    int type = ctx.find_memory_type(type_bits, flags);
    if (type >= 0) return uint32_t(type);
  }
  throw std::runtime_error("no memory type fits the resource (type bits " + std::to_string(type_bits) + ")");
}

static bool is_host_visible(MemoryLocation location) { return location != MemoryLocation::DeviceLocal; }

// The memory of `label`, checked against the heap and allocation limits first.
static VkDeviceMemory allocate(const Context& ctx, VkDeviceSize size, uint32_t type, const ResourceLabel& label) {
  check_memory_limits(ctx, size, type, label);
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = size;
  info.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  if (VkResult result = vkAllocateMemory(ctx.device(), &info, nullptr, &memory); result < 0)
    throw_allocation_failure(result, size, label);
  ctx.set_name(memory, VK_OBJECT_TYPE_DEVICE_MEMORY, label.name + " memory");
  return memory;
}

// ---------------------------------------------------------------- MemoryHeap

MemoryHeap::MemoryHeap(const Context& ctx, VkDeviceSize size, uint32_t memory_type_bits, MemoryLocation location,
                       const std::string& name, const std::string& sized_by)
    : ctx_(&ctx), size_(size) {
  memory_type_ = choose_memory_type(ctx, memory_type_bits, location);
  memory_ = allocate(ctx, size, memory_type_, {name, sized_by});
  if (is_host_visible(location)) VK_CHECK(vkMapMemory(ctx.device(), memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

MemoryHeap::~MemoryHeap() { release(); }

MemoryHeap::MemoryHeap(MemoryHeap&& other) noexcept { *this = std::move(other); }

MemoryHeap& MemoryHeap::operator=(MemoryHeap&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    memory_type_ = other.memory_type_;
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void MemoryHeap::release() {
  if (memory_) ctx_->destroy_named(memory_, VK_OBJECT_TYPE_DEVICE_MEMORY, vkFreeMemory);
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

// A placed resource must be aligned, fit the heap and accept the heap's memory type.
static void check_placement(const VkMemoryRequirements& reqs, const MemoryHeap& heap, VkDeviceSize offset,
                            const std::string& what) {
  bool fits = offset % reqs.alignment == 0 && offset + reqs.size <= heap.size() &&
              (reqs.memoryTypeBits & (1u << heap.memory_type())) != 0;
  if (!fits)
    throw std::runtime_error(what + " cannot be placed at offset " + std::to_string(offset) + " in a heap of " +
                             std::to_string(heap.size()) + " bytes");
}

// ---------------------------------------------------------------- Buffer

static VkBufferCreateInfo buffer_info(const BufferDesc& desc) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = desc.size;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  return info;
}

// The driver's requirements, after the checks that make asking valid; the memory they
// need is checked too, so a plan fails on the resource, not later on its heap.
static MemoryRequirements checked_requirements(const Context& ctx, const VkMemoryRequirements& reqs,
                                               MemoryLocation location, const ResourceLabel& label) {
  check_memory_limits(ctx, reqs.size, choose_memory_type(ctx, reqs.memoryTypeBits, location), label);
  return {reqs.size, reqs.alignment, reqs.memoryTypeBits};
}

MemoryRequirements memory_requirements(const Context& ctx, const BufferDesc& desc) {
  check_buffer_limits(ctx, desc);
  VkBufferCreateInfo create = buffer_info(desc);
  VkDeviceBufferMemoryRequirements query{VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS};
  query.pCreateInfo = &create;
  VkMemoryRequirements2 reqs{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
  vkGetDeviceBufferMemoryRequirements(ctx.device(), &query, &reqs);
  return checked_requirements(ctx, reqs.memoryRequirements, desc.location, {desc.name, desc.sized_by});
}

static VkBuffer create_buffer_handle(const Context& ctx, const BufferDesc& desc) {
  if (desc.size == 0) throw std::runtime_error("buffer '" + desc.name + "' has size 0");
  memory_requirements(ctx, desc);  // checks it against the device's limits
  VkBufferCreateInfo info = buffer_info(desc);
  VkBuffer buffer = VK_NULL_HANDLE;
  if (VkResult result = vkCreateBuffer(ctx.device(), &info, nullptr, &buffer); result < 0)
    throw_allocation_failure(result, desc.size, {desc.name, desc.sized_by});
  ctx.set_name(buffer, VK_OBJECT_TYPE_BUFFER, desc.name);
  return buffer;
}

Buffer Buffer::create(const Context& ctx, const BufferDesc& desc) {
  Buffer b;
  b.ctx_ = &ctx;
  b.size_ = desc.size;
  b.name_ = desc.name;
  b.buffer_ = create_buffer_handle(ctx, desc);
  VkMemoryRequirements reqs;
  vkGetBufferMemoryRequirements(ctx.device(), b.buffer_, &reqs);
  uint32_t type = choose_memory_type(ctx, reqs.memoryTypeBits, desc.location);
  b.own_memory_ = allocate(ctx, reqs.size, type, {desc.name, desc.sized_by});
  VK_CHECK(vkBindBufferMemory(ctx.device(), b.buffer_, b.own_memory_, 0));
  if (is_host_visible(desc.location)) VK_CHECK(vkMapMemory(ctx.device(), b.own_memory_, 0, VK_WHOLE_SIZE, 0, &b.mapped_));
  return b;
}

Buffer Buffer::create_placed(const Context& ctx, const BufferDesc& desc, const MemoryHeap& heap, VkDeviceSize offset) {
  Buffer b;
  b.ctx_ = &ctx;
  b.size_ = desc.size;
  b.name_ = desc.name;
  b.buffer_ = create_buffer_handle(ctx, desc);
  VkMemoryRequirements reqs;
  vkGetBufferMemoryRequirements(ctx.device(), b.buffer_, &reqs);
  check_placement(reqs, heap, offset, "buffer '" + desc.name + "'");  // b's destructor cleans up on throw
  VK_CHECK(vkBindBufferMemory(ctx.device(), b.buffer_, heap.handle(), offset));
  if (heap.mapped()) b.mapped_ = static_cast<char*>(heap.mapped()) + offset;
  return b;
}

Buffer Buffer::region(const Buffer& parent, VkDeviceSize offset, VkDeviceSize size, std::string name) {
  if (offset + size > parent.size())
    throw std::runtime_error("region '" + name + "' (" + std::to_string(size) + " bytes at " + std::to_string(offset) +
                             ") overflows buffer '" + parent.name() + "' of " + std::to_string(parent.size()) + " bytes");
  Buffer b;
  b.ctx_ = parent.ctx_;
  b.buffer_ = parent.buffer_;
  b.size_ = size;
  b.offset_ = parent.offset_ + offset;
  b.owns_handle_ = false;
  b.name_ = std::move(name);
  if (parent.mapped_) b.mapped_ = static_cast<char*>(parent.mapped_) + offset;
  return b;
}

Buffer::~Buffer() { release(); }
Buffer::Buffer(Buffer&& other) noexcept { *this = std::move(other); }

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    own_memory_ = std::exchange(other.own_memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    offset_ = std::exchange(other.offset_, 0);
    owns_handle_ = std::exchange(other.owns_handle_, true);
    mapped_ = std::exchange(other.mapped_, nullptr);
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::release() {
  if (buffer_ && owns_handle_) ctx_->destroy_named(buffer_, VK_OBJECT_TYPE_BUFFER, vkDestroyBuffer);
  if (own_memory_) ctx_->destroy_named(own_memory_, VK_OBJECT_TYPE_DEVICE_MEMORY, vkFreeMemory);
  buffer_ = VK_NULL_HANDLE;
  own_memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

void Buffer::upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (!mapped_) throw std::runtime_error("buffer '" + name_ + "' is not host visible");
  if (offset + bytes > size_) throw std::runtime_error("upload overflows buffer '" + name_ + "'");
  std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
}

// ---------------------------------------------------------------- Image

bool is_depth_format(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
    case VK_FORMAT_X8_D24_UNORM_PACK32: return true;
    default: return false;
  }
}

uint32_t format_bytes_per_texel(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT: return 1;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_D16_UNORM: return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT: return 16;
    default: throw std::runtime_error("format_bytes_per_texel: unsupported format " + std::to_string(int(format)));
  }
}

VkImageType image_type_of(const ImageDesc& desc) {
  return desc.depth > 1 || desc.volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
}

static VkImageCreateInfo image_info(const ImageDesc& desc) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = image_type_of(desc);
  info.format = desc.format;
  info.extent = {desc.width, desc.height, desc.depth};
  info.mipLevels = desc.mip_levels;
  info.arrayLayers = desc.array_layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return info;
}

MemoryRequirements memory_requirements(const Context& ctx, const ImageDesc& desc) {
  check_image_limits(ctx, desc);
  VkImageCreateInfo create = image_info(desc);
  VkDeviceImageMemoryRequirements query{VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS};
  query.pCreateInfo = &create;
  VkMemoryRequirements2 reqs{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
  vkGetDeviceImageMemoryRequirements(ctx.device(), &query, &reqs);
  return checked_requirements(ctx, reqs.memoryRequirements, MemoryLocation::DeviceLocal, {desc.name, desc.sized_by});
}

void Image::create_image(const Context& ctx, const ImageDesc& desc) {
  ctx_ = &ctx;
  desc_ = desc;
  const VkDeviceSize bytes = memory_requirements(ctx, desc).size;  // checks it against the device's limits
  VkImageCreateInfo info = image_info(desc);
  if (VkResult result = vkCreateImage(ctx.device(), &info, nullptr, &image_); result < 0)
    throw_allocation_failure(result, bytes, {desc.name, desc.sized_by});
  ctx.set_name(image_, VK_OBJECT_TYPE_IMAGE, desc.name);
}

VkImageAspectFlags Image::aspect() const {
  return is_depth_format(desc_.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

VkImageSubresourceRange Image::full_range() const {
  return {aspect(), 0, desc_.mip_levels, 0, desc_.array_layers};
}

static VkImageViewType view_type_of(const ImageDesc& desc) {
  if (desc.depth > 1 || desc.volume) return VK_IMAGE_VIEW_TYPE_3D;
  return desc.array_layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
}

void Image::create_view() {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = image_;
  info.viewType = view_type_of(desc_);
  info.format = desc_.format;
  info.subresourceRange = full_range();
  VK_CHECK(vkCreateImageView(ctx_->device(), &info, nullptr, &view_));
  ctx_->set_name(view_, VK_OBJECT_TYPE_IMAGE_VIEW, desc_.name + " view");
  mip_views_.assign(desc_.mip_levels, VK_NULL_HANDLE);
}

VkImageView Image::mip_view(uint32_t level) const {
  if (level >= desc_.mip_levels) throw std::runtime_error("image '" + desc_.name + "': mip level out of range");
  if (!mip_views_[level]) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image_;
    info.viewType = view_type_of(desc_);
    info.format = desc_.format;
    info.subresourceRange = {aspect(), level, 1, 0, desc_.array_layers};
    VK_CHECK(vkCreateImageView(ctx_->device(), &info, nullptr, &mip_views_[level]));
    ctx_->set_name(mip_views_[level], VK_OBJECT_TYPE_IMAGE_VIEW, desc_.name + " mip " + std::to_string(level));
  }
  return mip_views_[level];
}

Image Image::create(const Context& ctx, const ImageDesc& desc) {
  Image img;
  img.create_image(ctx, desc);
  VkMemoryRequirements reqs;
  vkGetImageMemoryRequirements(ctx.device(), img.image_, &reqs);
  uint32_t type = choose_memory_type(ctx, reqs.memoryTypeBits, MemoryLocation::DeviceLocal);
  img.own_memory_ = allocate(ctx, reqs.size, type, {desc.name, desc.sized_by});
  VK_CHECK(vkBindImageMemory(ctx.device(), img.image_, img.own_memory_, 0));
  img.create_view();
  return img;
}

Image Image::create_placed(const Context& ctx, const ImageDesc& desc, const MemoryHeap& heap, VkDeviceSize offset) {
  Image img;
  img.create_image(ctx, desc);
  VkMemoryRequirements reqs;
  vkGetImageMemoryRequirements(ctx.device(), img.image_, &reqs);
  check_placement(reqs, heap, offset, "image '" + desc.name + "'");  // img's destructor cleans up on throw
  VK_CHECK(vkBindImageMemory(ctx.device(), img.image_, heap.handle(), offset));
  img.create_view();
  return img;
}

Image Image::borrow(const Context& ctx, VkImage image, VkImageView view, const ImageDesc& desc) {
  Image img;
  img.ctx_ = &ctx;
  img.desc_ = desc;
  img.image_ = image;
  img.view_ = view;
  img.borrowed_ = true;
  img.mip_views_.assign(desc.mip_levels, VK_NULL_HANDLE);
  return img;
}

Image::~Image() { release(); }
Image::Image(Image&& other) noexcept { *this = std::move(other); }

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    mip_views_ = std::move(other.mip_views_);
    own_memory_ = std::exchange(other.own_memory_, VK_NULL_HANDLE);
    borrowed_ = std::exchange(other.borrowed_, false);
    desc_ = std::move(other.desc_);
  }
  return *this;
}

void Image::release() {
  if (!ctx_) return;
  for (VkImageView v : mip_views_)
    if (v) ctx_->destroy_named(v, VK_OBJECT_TYPE_IMAGE_VIEW, vkDestroyImageView);
  mip_views_.clear();
  if (view_ && !borrowed_) ctx_->destroy_named(view_, VK_OBJECT_TYPE_IMAGE_VIEW, vkDestroyImageView);
  if (image_ && !borrowed_) ctx_->destroy_named(image_, VK_OBJECT_TYPE_IMAGE, vkDestroyImage);
  if (own_memory_) ctx_->destroy_named(own_memory_, VK_OBJECT_TYPE_DEVICE_MEMORY, vkFreeMemory);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  own_memory_ = VK_NULL_HANDLE;
}

// ---------------------------------------------------------------- Sampler

Sampler::Sampler(const Context& ctx, const SamplerDesc& desc) : ctx_(&ctx) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = desc.filter;
  info.minFilter = desc.min_filter.value_or(desc.filter);
  info.mipmapMode = desc.mip_mode;
  info.addressModeU = info.addressModeW = desc.address;
  info.addressModeV = desc.address_v.value_or(desc.address);
  info.compareEnable = desc.compare ? VK_TRUE : VK_FALSE;
  info.compareOp = desc.compare_op;
  info.maxLod = desc.max_lod;
  info.borderColor = desc.border;
  VK_CHECK(vkCreateSampler(ctx.device(), &info, nullptr, &sampler_));
  ctx.set_name(sampler_, VK_OBJECT_TYPE_SAMPLER, desc.name.empty() ? "sampler" : desc.name);
}

Sampler::~Sampler() {
  if (sampler_) ctx_->destroy_named(sampler_, VK_OBJECT_TYPE_SAMPLER, vkDestroySampler);
}

Sampler::Sampler(Sampler&& other) noexcept { *this = std::move(other); }

Sampler& Sampler::operator=(Sampler&& other) noexcept {
  if (this != &other) {
    if (sampler_) ctx_->destroy_named(sampler_, VK_OBJECT_TYPE_SAMPLER, vkDestroySampler);
    ctx_ = std::exchange(other.ctx_, nullptr);
    sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

BufferRange::BufferRange(const Buffer& whole) : buffer(whole.handle()), size(whole.size()), offset(whole.offset()) {}

}  // namespace avsm::gpu
