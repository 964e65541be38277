#include "renderer/scene_renderer.h"

#include <utility>

#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "passes/frame/lights.h"
#include "shared/area_shadows.h"
#include "passes/shadows/shadow_pass_list_builder.h"

namespace avsm::renderer {

static gpu::Image output_image(gpu::Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                               VkImageUsageFlags usage, const char* name) {
  gpu::ImageDesc desc;
  desc.width = width;
  desc.height = height;
  desc.format = format;
  desc.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = name;
  desc.sized_by = passes::kCameraSizeSetting;
  return gpu::Image::create(ctx, desc);
}

SceneRenderer::SceneRenderer(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const scene::Scene& scene,
                             uint32_t width, uint32_t height, const passes::ShadowOptions& shadow_options)
    : ctx_(ctx),
      width_(width),
      height_(height),
      opaque_(ctx, shaders),
      area_shadow_filter_(ctx, shaders),
      hair_(ctx, shaders),
      volumes_(ctx, shaders),
      cache_(ctx, shaders),
      cached_march_(ctx, shaders),
      upsample_(ctx, shaders),
      hair_lighting_(ctx, shaders),
      fog_media_(ctx),
      fog_scattering_(ctx, shaders),
      fog_integration_(ctx, shaders),
      fog_apply_(ctx, shaders),
      shadows_(ctx, shaders),
      shaders_(shaders),
      tonemap_(ctx, shaders) {
  set_scene(scene, shadow_options);
  create_outputs();
}

void SceneRenderer::set_scene(const scene::Scene& scene, const passes::ShadowOptions& shadow_options) {
  // Frames in flight read the buffers replaced here, and their results (probes, capture
  // figures) belong to the scene they were declared with: callers finish them first
  // (LiveRenderer's before_change), which makes this wait free; it guards those that do not.
  // Lights that only move need none of it (place_light).
  vkDeviceWaitIdle(ctx_.device());
  lights_ = scene.lights;
  light_count_ = uint32_t(scene.lights.size());
  fitted_bounds_ = scene.bounds;
  mesh_objects_ = passes::mesh_caster_objects(scene);
  volume_objects_.clear();
  const std::vector<passes::CasterObject> objects = passes::scene_caster_objects(scene);
  for (uint32_t o = 0; o < objects.size(); ++o)
    if (objects[o].kind == passes::CasterObject::Kind::volume) volume_objects_.push_back(o);
  light_buffers_.create(ctx_, passes::light_buffer_desc(light_count_, "scene lights"));
  opaque_.set_scene(scene);
  hair_.set_scene(scene);
  volumes_.set_volumes(scene.volumes);
  next_volumes_.clear();
  set_volume_shading(scene.volume_shading);
  fog_media_.set_fog(scene.fog, scene.bounds);
  shadows_.set_scene(scene, shadow_options);

  // Output passes enabled before follow the new lights.
  if (probes_ && probe_normals_.empty()) probes_->set_points(probe_points_, light_count_);
  if (probes_ && !probe_normals_.empty()) probes_->set_surface_points(probe_points_, probe_normals_, light_count_);
  if (light_images_) light_images_->set_lights(shadows_);
  if (resolution_) resolution_->set_size(width_, height_, light_count_);
  if (level_overlay_ && *level_overlay_ >= light_count_) level_overlay_.reset();
  if (quality_ && shadows_.has_reference()) {
    enable_quality();
  } else {
    quality_.reset();
    hair_quality_.reset();
  }
  if (texel_curves_) {
    std::erase_if(texel_samples_, [&](const passes::TexelSample& s) { return !texel_sample_problem(s).empty(); });
    if (texel_samples_.empty())
      texel_curves_.reset();
    else
      texel_curves_->set_texel_samples(texel_samples_);
  }
}

void SceneRenderer::set_volume_shading(const scene::VolumeShading& shading) {
  if (shading.resolution_divisor != 1 && shading.resolution_divisor != 2 && shading.resolution_divisor != 4)
    throw std::invalid_argument("volume shading: the resolution divisor must be 1, 2 or 4, got " +
                                std::to_string(shading.resolution_divisor));
  if (!(shading.step_voxels >= 0.125f && shading.step_voxels <= 4.0f))
    throw std::invalid_argument("volume shading: the march step must be 0.125 to 4 voxels, got " +
                                std::to_string(shading.step_voxels));
  volume_shading_ = shading;
}

void SceneRenderer::set_size(uint32_t width, uint32_t height) {
  if (width == width_ && height == height_) return;
  // Frames in flight write the output images replaced here, and their callers read them
  // back when the frame finishes: callers finish them first (as for set_scene).
  vkDeviceWaitIdle(ctx_.device());
  width_ = width;
  height_ = height;
  create_outputs();
  if (quality_) quality_->set_size(width_, height_, light_count_);
  if (resolution_) resolution_->set_size(width_, height_, light_count_);
}

void SceneRenderer::set_frames_in_flight(uint32_t count) {
  passes::check_frames_in_flight(count);
  vkDeviceWaitIdle(ctx_.device());  // every per-slot buffer is made again, for another ring of slots
  shadows_.set_frames_in_flight(count);
  light_buffers_.set_frames(ctx_, count);
  fog_media_.set_frames_in_flight(count);
  for (passes::ShadowProbePass* pass : {probes_.get(), texel_curves_.get()})
    if (pass) pass->set_frames_in_flight(count);
  if (quality_) quality_->set_frames_in_flight(count);
  if (hair_quality_) hair_quality_->set_frames_in_flight(count);
  if (resolution_) resolution_->set_frames_in_flight(count);
  finished_slot_ = 0;
}

void SceneRenderer::place_light(uint32_t light, const glm::vec3& position, const glm::vec3& direction) {
  scene::Light& moved = lights_.at(light);
  moved.position = position;
  moved.direction = direction;
  shadows_.place_light(light, position, direction);
}

void SceneRenderer::update_mesh(uint32_t mesh, const scene::Mesh& now) {
  const uint32_t object = mesh_objects_.at(mesh);
  if (!fitted_bounds_.contains(now.bounds))
    throw std::invalid_argument("mesh '" + now.name +
                                "' moved outside the bounds the shadow maps were fitted to; set the scene again "
                                "to fit them anew");
  vkDeviceWaitIdle(ctx_.device());  // frames in flight read the vertices as static data
  opaque_.update_mesh(mesh, now);
  if (object != passes::kNoCasterObject) shadows_.caster_moved(object, now.bounds);
}

void SceneRenderer::show_volume_frame(uint32_t volume, std::shared_ptr<const passes::PreparedVolume> part) {
  if (volume >= volume_objects_.size())
    throw std::out_of_range("SceneRenderer::show_volume_frame: volume " + std::to_string(volume) + " of " +
                            std::to_string(volume_objects_.size()));
  if (!fitted_bounds_.contains(part->volume->world_bounds))
    throw std::invalid_argument("volume '" + part->volume->name +
                                "' reaches outside the bounds the shadow maps were fitted to; set the scene again "
                                "to fit them anew");
  if (next_volumes_.empty()) next_volumes_ = volumes_.prepared();
  shadows_.caster_moved(volume_objects_[volume], part->volume->world_bounds);
  next_volumes_[volume] = std::move(part);
}

void SceneRenderer::finish_frame(uint32_t slot) {
  shadows_.finish_frame(slot);
  finished_slot_ = slot;
}

void SceneRenderer::create_outputs() {
  hdr_ = output_image(ctx_, width_, height_, passes::OpaquePass::kColorFormat,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT, "hdr color");
  ldr_ = output_image(ctx_, width_, height_, passes::TonemapPass::kOutputFormat, VK_IMAGE_USAGE_STORAGE_BIT,
                      "tonemapped");
}

passes::ShadowCasters SceneRenderer::shadow_casters() const {
  return {opaque_.casters(), hair_.casters(), volumes_.casters()};
}

passes::ShadowPassList SceneRenderer::describe_shadows(const passes::View& view, uint32_t slot) {
  return passes::describe_shadow_frame(shadows_, ctx_, view, shadow_casters(), slot);
}

rg::Graph SceneRenderer::build_frame(const passes::View& view, uint32_t slot) {
  if (slot >= frames_in_flight())
    throw std::invalid_argument("SceneRenderer::build_frame: frame slot " + std::to_string(slot) + " of " +
                                std::to_string(frames_in_flight()) + " frames in flight");
  rg::Graph graph;
  // A volume sequence's new frames, copied in first (the slot's staging is free: its frame completed).
  if (!next_volumes_.empty()) volumes_.stream(std::exchange(next_volumes_, {}), slot);
  volumes_.add_upload(graph, slot);
  // Both outputs are read back after the frame, hence TransferSrc as their final state;
  // the next frame's writes wait for those reads (the frame before may still run).
  const rg::ImportState read_back = rg::ImportState::of(rg::Usage::TransferSrc);
  rg::TextureHandle hdr = rg::vulkan::import(graph, "hdr color", hdr_, passes::rewritten_after(read_back), read_back);
  rg::TextureHandle ldr = rg::vulkan::import(graph, "tonemapped", ldr_, passes::rewritten_after(read_back), read_back);
  passes::write_lights(light_buffers_[slot], lights_);  // the slot's previous frame has completed

  // What every camera pass reads this frame, published once.
  passes::FrameInputs frame;
  frame.view = view;
  frame.volumes = &volumes_;
  frame.shading = volume_shading_;
  frame.lights = &light_buffers_[slot];
  frame.light_count = light_count_;
  frame.lookups_per_point = shadows_.lookups_per_point();
  frame.shadows = shadows_.add_to_graph(graph, view, shadow_casters(), slot);
  frame.light_views = &shadows_.light_views();
  const passes::ShadowInputs& shadows = frame.shadows;
  frame.fog = fog_media_.write(slot, view);

  // Area lights with many virtual lights: a subset per pixel, filtered.
  const uint32_t area_tile = area_shadow_filter_tile();
  passes::OpaquePass::Outputs opaque = opaque_.add_to_graph(graph, hdr, frame, area_tile > 0);
  rg::TextureHandle color = opaque.color;
  if (area_tile > 0)
    color = area_shadow_filter_.add_to_graph(graph, color, opaque.area_light, opaque.depth, view, area_tile);
  color = add_fog(graph, color, opaque.depth, frame);
  color = add_volumes(graph, color, opaque.depth, frame);
  // Hair after the smoke: each strand fragment brings the smoke in front of it (per vertex).
  // Per fragment is the reference's; hidden volumes keep the fast per-vertex lighting (per
  // fragment made the hair pass 18x slower), and the volume comparison asks for the
  // reference's when its hidden frame stands in for the reference without smoke.
  const bool per_fragment =
      hair_per_fragment_.value_or(volume_shading_.mode == scene::VolumeShading::Mode::reference);
  const rg::BufferHandle hair_lights = hair_lighting_.add_to_graph(graph, hair_, frame);
  color = hair_.add_to_graph(graph, color, opaque.depth, hair_lights, per_fragment, frame);

  ldr = tonemap_.add_to_graph(graph, color, ldr, exposure_);
  if (quality_)
    quality_->add_to_graph(graph, opaque.depth, frame);
  if (hair_quality_) hair_quality_->add_to_graph(graph, opaque.depth, frame);
  if (resolution_figures_ || level_overlay_) {
    const rg::BufferHandle levels = resolution_->add_to_graph(graph, opaque.depth, frame);
    if (level_overlay_) level_overlay_pass_->add_to_graph(graph, ldr, levels, *level_overlay_);
  }
  if (probes_) probes_->add_to_graph(graph, frame.shadows);
  if (texel_curves_) texel_curves_->add_to_graph(graph, frame.shadows);
  if (light_images_) light_images_->add_to_graph(graph, shadows, shadows_);
  return graph;
}

// The widest tile of the area lights whose surface lookups take subsets of their virtual
// lights (shared/area_shadows.h), or 0 when none do (or they are looked up exactly).
uint32_t SceneRenderer::area_shadow_filter_tile() const {
  const bool filtered = area_shadows_filtered_.value_or(volume_shading_.mode != scene::VolumeShading::Mode::reference);
  uint32_t tile = 0;
  if (!filtered) return tile;
  for (const scene::Light& light : lights_)
    if (scene::is_area_light(light.type) && shared::area_shadow_takes_subsets(uint32_t(light.virtual_lights)))
      tile = std::max(tile, shared::area_shadow_tile(uint32_t(light.virtual_lights)));
  return tile;
}

rg::TextureHandle SceneRenderer::add_fog(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                         passes::FrameInputs& frame) {
  if (!fog_media_.enabled()) return color;
  const rg::TextureHandle froxels = fog_scattering_.add_to_graph(graph, frame);
  fog_integration_.add_to_graph(graph, froxels, frame);
  // The fog first over the surfaces and the background; the smoke and the hair, nearer,
  // go over it with the fog in front of them (common/fog.glsl).
  const bool per_pixel = fog_per_pixel_.value_or(volume_shading_.mode == scene::VolumeShading::Mode::reference);
  return fog_apply_.add_to_graph(graph, color, depth, frame, per_pixel);
}

rg::TextureHandle SceneRenderer::add_volumes(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                             passes::FrameInputs& frame) {
  if (volumes_.volume_count() == 0 || !frame.smoke_visible()) return color;
  if (volume_shading_.mode == scene::VolumeShading::Mode::reference)
    return volumes_.add_to_graph(graph, color, depth, frame);
  cache_.add_to_graph(graph, frame);
  const passes::VolumeMarchImage march = cached_march_.add_to_graph(graph, depth, frame);
  return upsample_.add_to_graph(graph, color, depth, march, frame);
}

void SceneRenderer::set_probes(const std::vector<glm::vec3>& points) {
  if (!probes_) probes_ = new_probe_pass();
  probe_points_ = points;
  probe_normals_.clear();
  probes_->set_points(points, light_count_);
}

void SceneRenderer::set_surface_probes(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals) {
  if (!probes_) probes_ = new_probe_pass();
  probes_->set_surface_points(points, normals, light_count_);
  probe_points_ = points;
  probe_normals_ = normals;
}

std::string SceneRenderer::texel_sample_problem(const passes::TexelSample& sample) const {
  if (sample.light >= shadows_.light_count())
    return "texel sample of light " + std::to_string(sample.light) + ": the scene has " +
           std::to_string(shadows_.light_count()) + " lights";
  const uint32_t resolution = shadows_.light_views()[sample.light].resolution;
  if (sample.texel.x >= resolution || sample.texel.y >= resolution)
    return "texel (" + std::to_string(sample.texel.x) + ", " + std::to_string(sample.texel.y) + ") is outside light " +
           std::to_string(sample.light) + "'s " + std::to_string(resolution) + "x" + std::to_string(resolution) + " map";
  return {};
}

void SceneRenderer::set_texel_samples(const std::vector<passes::TexelSample>& samples) {
  for (const passes::TexelSample& sample : samples)
    if (std::string problem = texel_sample_problem(sample); !problem.empty()) throw std::invalid_argument(problem);
  if (!texel_curves_) texel_curves_ = new_probe_pass();
  texel_samples_ = samples;
  texel_curves_->set_texel_samples(samples);
}

std::vector<passes::TexelSampleResult> SceneRenderer::texel_results() const {
  return texel_curves_ ? texel_curves_->texel_results(finished_slot_) : std::vector<passes::TexelSampleResult>{};
}

void SceneRenderer::enable_quality() {
  if (!shadows_.has_reference())
    throw std::logic_error("SceneRenderer::enable_quality: the shadow maps must keep the reference "
                           "(ShadowOptions::keep_reference)");
  for (uint32_t light = 0; light < light_count_; ++light)
    if (!shadows_.has_reference(light))
      throw std::invalid_argument(passes::light_display_name(lights_.at(light), light) +
                                  ": its maps are paged, whose pages keep their exact reference only with "
                                  "ShadowOptions::keep_paged_reference; set it, or shadow.layout to \"dense\", for "
                                  "the quality figures");
  if (!quality_) quality_ = std::make_unique<passes::ShadowQualityPass>(ctx_, shaders_);
  quality_->set_frames_in_flight(frames_in_flight());
  quality_->set_size(width_, height_, light_count_);
  if (!hair_quality_) hair_quality_ = std::make_unique<passes::ShadowQualityHairPass>(ctx_, shaders_);
  hair_quality_->set_frames_in_flight(frames_in_flight());
  hair_quality_->set_hair(hair_, light_count_);
}

std::vector<float> SceneRenderer::hair_quality_results() const {
  return hair_quality_ ? hair_quality_->results(finished_slot_) : std::vector<float>{};
}

std::vector<passes::PixelShadowError> SceneRenderer::quality_results() const {
  return quality_ ? quality_->results(finished_slot_) : std::vector<passes::PixelShadowError>{};
}

void SceneRenderer::enable_resolution_figures() {
  create_resolution_pass();
  resolution_figures_ = true;
}

void SceneRenderer::create_resolution_pass() {
  if (resolution_) return;
  resolution_ = std::make_unique<passes::ShadowResolutionPass>(ctx_, shaders_);
  resolution_->set_frames_in_flight(frames_in_flight());
  resolution_->set_size(width_, height_, light_count_);
}

std::vector<passes::PixelShadowResolution> SceneRenderer::resolution_results() const {
  return resolution_ ? resolution_->results(finished_slot_) : std::vector<passes::PixelShadowResolution>{};
}

void SceneRenderer::set_level_overlay(std::optional<uint32_t> light) {
  if (light && *light >= light_count_)
    throw std::invalid_argument("shadow level overlay: light " + std::to_string(*light) + " of " +
                                std::to_string(light_count_) + " lights");
  if (light) {
    create_resolution_pass();
    if (!level_overlay_pass_) level_overlay_pass_ = std::make_unique<passes::ShadowLevelOverlayPass>(ctx_, shaders_);
  }
  level_overlay_ = light;
}

void SceneRenderer::enable_light_images() {
  if (!light_images_) light_images_ = std::make_unique<passes::ShadowDebugPass>(ctx_, shaders_);
  light_images_->set_lights(shadows_);
}

const std::vector<gpu::Image>& SceneRenderer::light_images() const {
  static const std::vector<gpu::Image> none;
  return light_images_ ? light_images_->images() : none;
}

std::unique_ptr<passes::ShadowProbePass> SceneRenderer::new_probe_pass() const {
  auto pass = std::make_unique<passes::ShadowProbePass>(ctx_, shaders_);
  pass->set_frames_in_flight(frames_in_flight());
  return pass;
}

std::vector<std::vector<float>> SceneRenderer::probe_results() const {
  return probes_ ? probes_->results(finished_slot_) : std::vector<std::vector<float>>{};
}

}  // namespace avsm::renderer
