#pragma once
// Renders a loaded scene through the frame graph: per light its transmittance
// map (passes/shadows/shadow_maps.h), then opaque geometry, fog volumes, hair, all shaded
// with those maps, then tonemapping. The volumes are seen the fast way (lighting
// cache, reduced-resolution march and upsample, per-vertex hair lighting) or the
// reference way (full-resolution march with shadow lookups along every ray), as the
// scene's volume_shading says. Owns the per-scene GPU data and the frame's output
// images; each frame declares its passes anew (the executor reuses the plan).
//
// Frames in flight (set_frames_in_flight; passes/frame/frames_in_flight.h): each frame is
// declared into a frame slot, whose lights, shadow parameters, counters and readbacks
// are its own; the caller records slot s again only after the frame it last held
// completed (renderer/frame_slots.h keeps a command buffer, fence and executor per slot).
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <memory>
#include <optional>
#include <string>

#include "gpu/resources.h"
#include "passes/camera/fog/fog_apply_pass.h"
#include "passes/camera/fog/fog_integration_pass.h"
#include "passes/camera/fog/fog_media.h"
#include "passes/camera/fog/fog_scattering_pass.h"
#include "passes/camera/hair/hair_lighting_pass.h"
#include "passes/camera/hair/hair_pass.h"
#include "passes/camera/surfaces/area_shadow_filter_pass.h"
#include "passes/camera/surfaces/opaque_pass.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/shadows/shadow_pass_list.h"
#include "passes/shadows/inspection/shadow_debug_pass.h"
#include "passes/shadows/inspection/shadow_probe_pass.h"
#include "passes/camera/quality/shadow_quality_hair_pass.h"
#include "passes/camera/quality/shadow_quality_pass.h"
#include "passes/camera/quality/shadow_level_overlay_pass.h"
#include "passes/camera/quality/shadow_resolution_pass.h"
#include "passes/camera/tonemap_pass.h"
#include "passes/frame/view.h"
#include "passes/camera/volumes/volume_cached_march_pass.h"
#include "passes/camera/volumes/volume_lighting_cache_pass.h"
#include "passes/camera/volumes/volume_pass.h"
#include "passes/camera/volumes/volume_upsample_pass.h"

#include "scene/scene.h"

namespace avsm::renderer {

class SceneRenderer {
 public:
  SceneRenderer(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const scene::Scene& scene, uint32_t width,
                uint32_t height, const passes::ShadowOptions& shadow_options = {});

  // Hands the renderer another scene (or the same one edited) without rebuilding
  // its pipelines: uploads geometry, hair, volumes and lights and sets the shadow
  // maps up again. Waits for the device to idle first. Probes, quality and light
  // images stay enabled; texel samples that no longer fit the maps are dropped.
  // Throws std::invalid_argument for a scene the passes cannot render; the
  // renderer is then left half-updated, so set the previous scene again.
  void set_scene(const scene::Scene& scene, const passes::ShadowOptions& shadow_options);
  // New output size (waits for the device to idle).
  void set_size(uint32_t width, uint32_t height);
  // How many frames may be in flight, 1 to passes::kMaxFramesInFlight (1 until set):
  // frames are declared into slots 0..count-1. Waits for the device to idle. Throws
  // std::invalid_argument for another count.
  void set_frames_in_flight(uint32_t count);
  uint32_t frames_in_flight() const { return shadows_.frames_in_flight(); }
  // Moves light `light` for the next frame declared (its position and direction; the
  // frames in flight keep theirs). Throws std::out_of_range for a light the scene lacks.
  void place_light(uint32_t light, const glm::vec3& position, const glm::vec3& direction);
  // Mesh `mesh` (its index in the scene's meshes) as it now is: moved or deformed, with
  // the vertex count it had. Waits for the device to idle, uploads it, and tells the
  // shadow maps, which build again only the pages its old and new bounds overlap.
  // Throws std::invalid_argument for another vertex count, or for bounds that leave
  // those the lights were fitted to (set the scene again to fit them anew), and
  // std::out_of_range for a mesh the scene lacks.
  void update_mesh(uint32_t mesh, const scene::Mesh& now);
  // Volume `volume` shows `part` (a sequence's frame, prepared: passes/frame/volume_data.h)
  // from the next frame declared on: its data is staged for that frame's slot and copied
  // in by the frame itself, without waiting for the frames in flight, and the shadow maps
  // build again the pages its old and new bounds overlap. Throws std::out_of_range for a
  // volume the scene lacks, std::invalid_argument for bounds that leave those the lights
  // were fitted to (scene::Scene::bounds holds every frame of its sequences).
  void show_volume_frame(uint32_t volume, std::shared_ptr<const passes::PreparedVolume> part);
  const passes::VolumePass::StreamStats& volume_stream_stats() const { return volumes_.stream_stats(); }
  void set_exposure(float exposure) { exposure_ = exposure; }
  // How the camera sees the volumes; set_scene() takes the scene's. Throws
  // std::invalid_argument for a divisor other than 1, 2, 4 or a step outside 0.125..4 voxels.
  void set_volume_shading(const scene::VolumeShading& shading);
  const scene::VolumeShading& volume_shading() const { return volume_shading_; }
  // Hair shading per fragment (the reference's) or per vertex (the fast path's); unset:
  // per fragment in the reference volume shading only. Lets a test look at the fast path's
  // smoke-hair compositing alone, and the volume comparison shade its hidden frame as the
  // reference.
  void set_hair_lighting_per_fragment(std::optional<bool> per_fragment) { hair_per_fragment_ = per_fragment; }
  std::optional<bool> hair_lighting_per_fragment() const { return hair_per_fragment_; }
  // The fog (scene/fog.h); set_scene() takes the scene's. Off: the frame declares no fog
  // passes and composites none, the settings kept (a host's switch, the viewer's).
  void set_fog(const scene::Fog& fog) { fog_media_.set_fog(fog, fitted_bounds_); }
  const scene::Fog& fog() const { return fog_media_.fog(); }
  void set_fog_enabled(bool enabled) { fog_media_.set_enabled(enabled); }
  bool fog_enabled() const { return fog_media_.enabled(); }
  // The fog over the surfaces marched per pixel (the reference's) or read from the froxel
  // grid (the fast path's); unset: per pixel in the reference volume shading only. Lets
  // the fog be measured against its reference alone.
  void set_fog_marched_per_pixel(std::optional<bool> per_pixel) { fog_per_pixel_ = per_pixel; }
  // Area lights' soft shadows on surfaces from a subset of their virtual lights per pixel,
  // filtered in screen space (passes/camera/surfaces/area_shadow_filter_pass.h), or from
  // every virtual light at every pixel (exact); unset: filtered, except in the reference
  // volume shading.
  void set_area_shadows_filtered(std::optional<bool> filtered) { area_shadows_filtered_ = filtered; }
  uint64_t density_atlas_bytes() const { return volumes_.atlas().bytes(); }
  // Cells in the last frame's lighting cache (0 in the reference path).
  uint64_t lighting_cache_cells() const { return volume_shading_.mode == scene::VolumeShading::Mode::fast ? cache_.cell_count() : 0; }
  float exposure() const { return exposure_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

  // Declares this frame's passes into frame slot `slot`, whose previous frame must have
  // completed (the output images come imported with the graph).
  rg::Graph build_frame(const passes::View& view, uint32_t slot = 0);

  // Probes every light's transmittance at these points in each frame (after the
  // camera passes); results in probe_results() once the frame completed.
  void set_probes(const std::vector<glm::vec3>& points);
  // Surface points with normals, looked up as the opaque pass does (probe_results()).
  void set_surface_probes(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals);
  std::vector<std::vector<float>> probe_results() const;

  // Evaluates single texels' curves (technique and exact reference) at chosen light
  // depths in each frame (passes/shadows/inspection/shadow_probe_pass.h, texel-curve mode); results in
  // texel_results() once the frame completed. Throws std::invalid_argument for a
  // light or texel the shadow maps do not have.
  void set_texel_samples(const std::vector<passes::TexelSample>& samples);
  std::vector<passes::TexelSampleResult> texel_results() const;

  // Measures every light's shadows against the exact reference, per camera pixel, at
  // the receivers the camera sees (passes/camera/quality/shadow_quality_pass.h), in each frame after
  // the camera passes. Needs ShadowOptions::keep_reference (std::logic_error without).
  // quality_results() once the frame completed: [light][pixel], row 0 at the top.
  void enable_quality();
  std::vector<passes::PixelShadowError> quality_results() const;
  // The same at the hair the camera sees (passes/camera/quality/shadow_quality_hair_pass.h):
  // [light * hair_receiver_count() + receiver], -1 where a strand vertex is not a receiver.
  std::vector<float> hair_quality_results() const;
  uint32_t hair_receiver_count() const { return hair_quality_ ? hair_quality_->receiver_count() : 0; }

  // Measures, per camera pixel and light, the level the opaque surface's lookup reads
  // and how wide its texels are on screen (passes/camera/quality/shadow_resolution_pass.h),
  // in each frame after the opaque pass; resolution_results() once the frame completed:
  // [light][pixel], row 0 at the top.
  void enable_resolution_figures();
  std::vector<passes::PixelShadowResolution> resolution_results() const;
  // Tints the tonemapped image's receivers of light `light` by the level their surface
  // lookup reads, and dims the rest (the viewer's overlay; it runs the resolution pass
  // while it is on); nullopt: off. Throws std::invalid_argument for a light
  // the scene does not have.
  void set_level_overlay(std::optional<uint32_t> light);
  std::optional<uint32_t> level_overlay() const { return level_overlay_; }

  // Renders a picture of every light's transmittance map in each frame
  // (passes/shadows/inspection/shadow_debug_pass.h); light_images() after the frame completed.
  void enable_light_images();
  const std::vector<gpu::Image>& light_images() const;

  // After the frame declared into `slot` completed (frames finish in the order they were
  // declared): reads its shadow capture counters (overflow, growth). The results below
  // (probes, texel curves, quality) are then that frame's, until the slot is declared again.
  void finish_frame(uint32_t slot = 0);
  const passes::ShadowMaps& shadows() const { return shadows_; }
  // The shadow work build_frame() would declare for `view` into `slot`, as a pass list
  // (passes/shadows/shadow_pass_list.h): what avsm-capture --dump-passes writes.
  passes::ShadowPassList describe_shadows(const passes::View& view, uint32_t slot = 0);
  // Fits the maps that follow the camera to `view` before the next frame (ShadowMaps::follow_camera).
  void fit_shadows_to(const passes::View& view) { shadows_.follow_camera(view); }

  // After the frame: linear HDR and tonemapped images, both in TRANSFER_SRC_OPTIMAL.
  const gpu::Image& hdr() const { return hdr_; }
  const gpu::Image& ldr() const { return ldr_; }
  static constexpr VkImageLayout kOutputLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;

 private:
  void create_outputs();
  // What casts: the scene's meshes, hair and volumes as the shadow passes take them.
  passes::ShadowCasters shadow_casters() const;
  // When the frame has fog: its froxel passes (frame.fog gets the grid), then its
  // composite onto `color` at the opaque `depth`; returns the new colour.
  rg::TextureHandle add_fog(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                            passes::FrameInputs& frame);
  // Adds the volume passes of the fast or the reference path; returns the new colour.
  // The fast path's lighting cache lands in `inputs.cache`.
  rg::TextureHandle add_volumes(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                passes::FrameInputs& frame);
  // Why the shadow maps cannot evaluate `sample` (empty when they can).
  std::string texel_sample_problem(const passes::TexelSample& sample) const;

  gpu::Context& ctx_;
  uint32_t width_, height_;
  float exposure_ = 1.0f;
  std::vector<glm::vec3> probe_points_;
  std::vector<glm::vec3> probe_normals_;  // set: the probes are surface points
  std::vector<passes::TexelSample> texel_samples_;
  std::unique_ptr<passes::ShadowProbePass> new_probe_pass() const;
  void create_resolution_pass();  // sized and ringed as the renderer is
  uint32_t area_shadow_filter_tile() const;

  std::vector<scene::Light> lights_;
  scene::Bounds fitted_bounds_;         // what the lights' maps were fitted to (the scene's bounds)
  std::vector<uint32_t> mesh_objects_;  // per scene mesh, its caster object (passes::mesh_caster_objects())
  std::vector<uint32_t> volume_objects_;  // per scene volume, its caster object
  std::vector<std::shared_ptr<const passes::PreparedVolume>> next_volumes_;  // shown from the next frame (empty: as they are)
  passes::FrameBuffers light_buffers_;  // the GpuLights, per frame slot, written as a frame is declared
  uint32_t light_count_ = 0;
  uint32_t finished_slot_ = 0;  // of the last frame finished: where its results are
  passes::OpaquePass opaque_;
  passes::AreaShadowFilterPass area_shadow_filter_;
  passes::HairPass hair_;
  passes::VolumePass volumes_;
  passes::VolumeLightingCachePass cache_;
  passes::VolumeCachedMarchPass cached_march_;
  passes::VolumeUpsamplePass upsample_;
  passes::HairLightingPass hair_lighting_;
  passes::FogMedia fog_media_;
  passes::FogScatteringPass fog_scattering_;
  passes::FogIntegrationPass fog_integration_;
  passes::FogApplyPass fog_apply_;
  scene::VolumeShading volume_shading_;
  std::optional<bool> hair_per_fragment_;
  std::optional<bool> fog_per_pixel_;
  std::optional<bool> area_shadows_filtered_;
  passes::ShadowMaps shadows_;
  std::unique_ptr<passes::ShadowProbePass> probes_;
  std::unique_ptr<passes::ShadowProbePass> texel_curves_;
  std::unique_ptr<passes::ShadowQualityPass> quality_;
  std::unique_ptr<passes::ShadowQualityHairPass> hair_quality_;
  std::unique_ptr<passes::ShadowResolutionPass> resolution_;
  std::unique_ptr<passes::ShadowLevelOverlayPass> level_overlay_pass_;
  std::optional<uint32_t> level_overlay_;
  bool resolution_figures_ = false;  // enable_resolution_figures(); the overlay runs the pass on its own
  std::unique_ptr<passes::ShadowDebugPass> light_images_;
  const gpu::ShaderLibrary& shaders_;

  passes::TonemapPass tonemap_;
  gpu::Image hdr_, ldr_;
};

}  // namespace avsm::renderer
