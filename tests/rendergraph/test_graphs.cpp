#include "test_graphs.h"

#include <string>

namespace rg_test {

using rg::PassBuilder;
using rg::QueueType;
using rg::Usage;

rg::TextureDesc texture_desc(uint32_t width, uint32_t height, VkFormat format) {
  rg::TextureDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  return desc;
}

namespace {

// A swapchain image: acquired (semaphore waited at colour output, contents undefined),
// presented afterwards.
rg::TextureHandle import_swapchain(rg::Graph& graph, const char* name) {
  const rg::ImportState acquired{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE,
                                 VK_IMAGE_LAYOUT_UNDEFINED};
  return graph.import_texture(name, texture_desc(256, 256, VK_FORMAT_B8G8R8A8_UNORM), acquired,
                              rg::ImportState::of(Usage::Present));
}

}  // namespace

rg::Graph diamond_graph() {
  rg::Graph graph;
  auto backbuffer = import_swapchain(graph, "backbuffer");
  rg::TextureHandle albedo, normal, depth, ao, direct;
  graph.add_pass("gbuffer", QueueType::Graphics, [&](PassBuilder& b) {
    albedo = b.write(b.create_texture("albedo", texture_desc(256, 256, VK_FORMAT_R8G8B8A8_UNORM)), Usage::ColorAttachment);
    normal = b.write(b.create_texture("normal", texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT)),
                     Usage::ColorAttachment);
    depth = b.write(b.create_texture("depth", texture_desc(256, 256, VK_FORMAT_D32_SFLOAT)),
                    Usage::DepthAttachmentWrite);
  }, no_execute);
  graph.add_pass("ssao", QueueType::Compute, [&](PassBuilder& b) {
    b.read(depth, Usage::Sampled);
    b.read(normal, Usage::Sampled);
    ao = b.write(b.create_texture("ao", texture_desc(256, 256, VK_FORMAT_R8_UNORM)), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("direct_light", QueueType::Compute, [&](PassBuilder& b) {
    b.read(albedo, Usage::Sampled);
    b.read(normal, Usage::Sampled);
    b.read(depth, Usage::Sampled);
    direct = b.write(b.create_texture("direct", texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT)),
                     Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("combine", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(ao, Usage::Sampled);
    b.read(direct, Usage::Sampled);
    backbuffer = b.write(backbuffer, Usage::ColorAttachment);
  }, no_execute);
  return graph;
}

rg::Graph culled_branch_graph() {
  rg::Graph graph;
  auto swapchain = import_swapchain(graph, "swapchain");
  rg::TextureHandle depth, hdr, heatmap;
  rg::BufferHandle luminance;
  graph.add_pass("depth_prepass", QueueType::Graphics, [&](PassBuilder& b) {
    depth = b.write(b.create_texture("depth", texture_desc(512, 512, VK_FORMAT_D32_SFLOAT)), Usage::DepthAttachmentWrite);
  }, no_execute);
  graph.add_pass("main", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(depth, Usage::DepthAttachmentRead);
    hdr = b.write(b.create_texture("hdr", texture_desc(512, 512, VK_FORMAT_R16G16B16A16_SFLOAT)), Usage::ColorAttachment);
  }, no_execute);
  graph.add_pass("luminance", QueueType::Compute, [&](PassBuilder& b) {
    b.read(hdr, Usage::Sampled);
    luminance = b.write(b.create_buffer("luminance", {1024}), Usage::StorageWrite);
  }, no_execute);
  // Debug branch: nothing consumes the overlay, so both passes are culled.
  graph.add_pass("debug_heatmap", QueueType::Compute, [&](PassBuilder& b) {
    b.read(depth, Usage::Sampled);
    heatmap = b.write(b.create_texture("heatmap", texture_desc(512, 512, VK_FORMAT_R8G8B8A8_UNORM)), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("debug_overlay", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(heatmap, Usage::Sampled);
    b.write(b.create_texture("overlay", texture_desc(512, 512, VK_FORMAT_R8G8B8A8_UNORM)), Usage::ColorAttachment);
  }, no_execute);
  graph.add_pass("tonemap", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(hdr, Usage::Sampled);
    swapchain = b.write(swapchain, Usage::ColorAttachment);
  }, no_execute);
  // Side effect: e.g. a copy the executor hands to a profiler; nothing in the graph reads it.
  graph.add_pass("depth_readback", QueueType::Transfer, [&](PassBuilder& b) {
    b.side_effect();
    b.read(depth, Usage::TransferSrc);
  }, no_execute);
  graph.mark_output(luminance);  // read by the CPU after the frame: keeps 'luminance' alive
  return graph;
}

rg::Graph multi_light_graph(int lights) {
  rg::Graph graph;
  auto frame = import_swapchain(graph, "frame");
  std::vector<rg::TextureHandle> maps;
  for (int i = 0; i < lights; ++i) {
    const std::string light = std::to_string(i);
    auto map = graph.import_texture("avsm_map_" + light, texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT),
                                    rg::ImportState::of(Usage::Sampled), rg::ImportState::of(Usage::Sampled));
    rg::TextureHandle head;
    rg::BufferHandle nodes;
    graph.add_pass("capture_" + light, QueueType::Graphics, [&](PassBuilder& b) {
      head = b.write(b.create_texture("head_" + light, texture_desc(512, 512, VK_FORMAT_R32_UINT)),
                     Usage::StorageReadWrite);
      nodes = b.write(b.create_buffer("nodes_" + light, {4u << 20}), Usage::StorageWrite);
    }, no_execute);
    graph.add_pass("sort_" + light, QueueType::Compute, [&](PassBuilder& b) {
      b.read(head, Usage::StorageRead);
      nodes = b.read_write(nodes, Usage::StorageReadWrite);
      b.write(b.create_buffer("sort_scratch_" + light, {2u << 20}), Usage::StorageReadWrite);
    }, no_execute);
    graph.add_pass("resolve_" + light, QueueType::Compute, [&](PassBuilder& b) {
      b.read(head, Usage::StorageRead);
      b.read(nodes, Usage::StorageRead);
      map = b.write(map, Usage::StorageWrite);
    }, no_execute);
    maps.push_back(map);
  }
  graph.add_pass("shade", QueueType::Graphics, [&](PassBuilder& b) {
    for (auto& map : maps) b.read(map, Usage::Sampled);
    frame = b.write(frame, Usage::ColorAttachment);
  }, no_execute);
  return graph;
}

rg::Graph buffer_raw_graph() {
  rg::Graph graph;
  auto color = graph.import_texture("color", texture_desc(256, 256, VK_FORMAT_R8G8B8A8_UNORM),
                                    rg::ImportState::of(Usage::ColorAttachment), rg::ImportState::of(Usage::Sampled));
  auto stats = graph.import_buffer("stats_readback", {64}, rg::ImportState::of(Usage::HostRead),
                                   rg::ImportState::of(Usage::HostRead));
  rg::BufferHandle instances, args, visible;
  graph.add_pass("upload", QueueType::Transfer, [&](PassBuilder& b) {
    instances = b.write(b.create_buffer("instances", {64 * 1024}), Usage::TransferDst);
  }, no_execute);
  graph.add_pass("cull", QueueType::Compute, [&](PassBuilder& b) {
    b.read(instances, Usage::StorageRead);
    args = b.write(b.create_buffer("draw_args", {256}), Usage::StorageWrite);
    visible = b.write(b.create_buffer("visible_ids", {16 * 1024}), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("draw", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(args, Usage::IndirectRead);
    b.read(visible, Usage::VertexRead);
    b.read(instances, Usage::StorageRead);
    color = b.read_write(color, Usage::ColorAttachment);
  }, no_execute);
  graph.add_pass("copy_stats", QueueType::Transfer, [&](PassBuilder& b) {
    b.read(args, Usage::TransferSrc);
    stats = b.write(stats, Usage::TransferDst);
  }, no_execute);
  return graph;
}

rg::Graph history_graph() {
  rg::Graph graph;
  auto history = graph.import_texture("taa_history", texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT),
                                      rg::ImportState::of(Usage::Sampled, QueueType::Compute),
                                      rg::ImportState::of(Usage::Sampled, QueueType::Compute));
  auto exposure = graph.import_buffer("exposure", {16}, rg::ImportState::of(Usage::StorageReadWrite, QueueType::Compute),
                                      rg::ImportState::of(Usage::StorageReadWrite, QueueType::Compute));
  auto swapchain = import_swapchain(graph, "swapchain");
  rg::TextureHandle scene, resolved;
  graph.add_pass("render", QueueType::Graphics, [&](PassBuilder& b) {
    scene = b.write(b.create_texture("scene", texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT)),
                    Usage::ColorAttachment);
  }, no_execute);
  graph.add_pass("taa", QueueType::Compute, [&](PassBuilder& b) {
    b.read(scene, Usage::Sampled);
    b.read(history, Usage::Sampled);  // last frame's result
    resolved = b.write(b.create_texture("taa_resolved", texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT)),
                       Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("auto_exposure", QueueType::Compute, [&](PassBuilder& b) {
    b.read(resolved, Usage::Sampled);
    exposure = b.read_write(exposure, Usage::StorageReadWrite);  // persistent across frames
  }, no_execute);
  graph.add_pass("update_history", QueueType::Transfer, [&](PassBuilder& b) {
    b.read(resolved, Usage::TransferSrc);
    history = b.write(history, Usage::TransferDst);  // next frame's history
  }, no_execute);
  graph.add_pass("tonemap", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(resolved, Usage::Sampled);
    b.read(exposure, Usage::UniformRead);
    swapchain = b.write(swapchain, Usage::ColorAttachment);
  }, no_execute);
  return graph;
}

// A map of 3 levels in one persistent buffer (level 0: 1024 bytes, level 1: 256, level 2:
// 64, then unused padding): resolved whole, each level built from the one above by reading
// its range and writing the next, then shaded from the whole buffer.
rg::Graph mip_chain_graph() {
  rg::Graph graph;
  const rg::BufferRange levels[3] = {{0, 1024}, {1024, 256}, {1280, 64}};
  auto map = graph.import_buffer("map", {1536}, rg::ImportState::none(), rg::ImportState::of(Usage::StorageRead));
  graph.add_pass("resolve", QueueType::Compute, [&](PassBuilder& b) {
    map = b.write(map, Usage::StorageWrite);
  }, no_execute);
  for (int level = 1; level < 3; ++level)
    graph.add_pass("mip " + std::to_string(level), QueueType::Compute, [&](PassBuilder& b) {
      b.read(map, Usage::StorageRead, levels[level - 1]);
      map = b.write(map, Usage::StorageWrite, levels[level]);
    }, no_execute);
  graph.add_pass("shade", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(map, Usage::StorageRead);
    b.side_effect();
  }, no_execute);
  return graph;
}

}  // namespace rg_test
