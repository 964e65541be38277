#pragma once
// The engine inside another renderer: adaptive volumetric shadow maps (Salvi et al.,
// EGSR 2010) for the host's own lights and casters, scheduled by the host's own frame
// graph and read by the host's own shading passes. This header needs no rendergraph/
// header; the engine's own graph is avsm/shadows_rendergraph.h.
//
//   // Once: create the device with what the engine needs, then adopt it.
//   avsm::gpu::DeviceRequirements needs(physical_device);    // extensions() + features()
//   ... vkCreateDevice(...) ...
//   avsm::gpu::Context context(avsm::gpu::AdoptedDevice{instance, physical_device, device, queue, family});
//   avsm::Shadows shadows(context, avsm::ShaderLocation::of_package());
//   shadows.set_light(light, casters_bounds);
//
//   shadows.set_frames_in_flight(2);                          // optional; 1 by default
//
//   // Every frame, in frame slot `slot` (0, 1, 0, 1, ...): its shadow passes as data, for
//   // the host's graph to schedule.
//   avsm::ShadowPassList frame = shadows.pass_list(camera, casters, slot);
//   for (avsm::ShadowPass& pass : frame.passes) {
//     // a node of the host's graph: pass.uses say which of frame.resources it reads and
//     // writes, with Vulkan stages, accesses and layouts; transients are the host's to
//     // allocate (size, format, usage given), persistent ones the engine's (handle given).
//     ... in the node's execute: pass.record(cmd, resolved);   // resolved[i]: resource i
//   }
//   ... the host's shading reads frame.lookup (declare its resources as storage reads)
//   submit with the slot's fence; record the next slot meanwhile;
//   when the slot's fence has signalled (before its next pass_list):
//   std::vector<avsm::LightStats> stats = shadows.finish_frame(slot);
//
// In the shading pass's GLSL (include directory: ShaderLocation::glsl_include_dir()):
//   #define AVSM_SHADOW_BINDING 4                  // any 4 free bindings
//   #define AVSM_SHADOW_PAGE_REQUESTS_BINDING 8    // paged lights: where the lookups ask for pages
//   #include "common/shadow_lookup.glsl"
//   float t = surface_light_transmittance(light_index, p, normal, to_light);  // surfaces
//   float t = light_transmittance(light_index, p);                            // volumes, hair
// The shader is the host's: compile it with compile_glsl() or with glslangValidator and
// -I <glsl_include_dir>. Its four buffers are ShadowLookupResources' parameters, atlas,
// list_heads and list_nodes (unused_buffer where one is absent); with paged lights a
// fifth, page_request_bits, which the lookups write (declare it as a storage write).
//
// Preconditions: every function below says what must hold of its arguments. set_lights()
// and pass_list() check all of it before they change anything, and a violation throws
// std::invalid_argument naming the function, the argument and what is wrong (e.g.
// "avsm::Shadows::pass_list: casters.strands: segments 0..5000 exceed the segment
// buffer (4096 bytes = 512 StrandSegment at stride 8)"). check_lights() and check_frame()
// run the same checks without a device. What lives only on the GPU (the indices'
// values, the segments' point and strand indices, the volumes' grids) cannot be checked
// here: indices must stay within their buffers, or the captures read out of bounds.
#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/pages/page_table.h"
#include "passes/shadows/shadow_clusters.h"
#include "passes/shadows/shadow_pass_list.h"
#include "scene/bounds.h"
#include "scene/fog.h"

namespace avsm::gpu {
class Context;
}

namespace avsm {

using passes::CasterVertex;
using passes::MeshCasters;
using passes::MeshDraw;
using passes::ShadowCasters;
using passes::kNoPassResource;
using passes::PassBufferRange;
using passes::PassQueue;
using passes::PassResource;
using passes::PassResourceState;
using passes::PassResourceUse;
using passes::ResolvedResource;
using passes::ShadowLookupResources;
using passes::ShadowPass;
using passes::ShadowPassList;
using passes::StrandCasters;
using passes::StrandParameters;
using passes::StrandSegment;
using passes::VolumeCasters;
using passes::FogLookupResources;
using scene::Bounds;
using scene::Fog;
using scene::FogBox;
using scene::FogGrid;
using scene::FogMedium;

// Where the engine's shaders are: GLSL under glsl_root/shaders/, SPIR-V compiled at
// build time under spirv_root/shaders/ (<name>.spv).
struct ShaderLocation {
  std::filesystem::path glsl_root;
  std::filesystem::path spirv_root;
  bool compile_from_source = false;  // compile the GLSL at run time instead of loading the SPIR-V

  // The include directory for a host shader's #include "common/shadow_lookup.glsl"
  // (Shadows::glsl_include_dirs() lists every folder the lookup's own includes need).
  std::filesystem::path glsl_include_dir() const { return glsl_root / "shaders"; }

  // The shaders of the package this code was built against: the installed package
  // (avsmConfig.cmake defines where it is, relative to itself, so the install can move)
  // or, inside the engine's own build, its source and build trees. Defined inline below
  // from AVSM_PACKAGE_GLSL_ROOT / AVSM_PACKAGE_SPIRV_ROOT, which linking avsm::shadows
  // defines; code built otherwise fills the two paths itself.
  static ShaderLocation of_package();
};

// rect, disk, sphere: area lights, their soft shadows the mean over `virtual_lights` maps
// (docs/embedding.md, "Area lights").
enum class LightType { directional, spot, point, rect, disk, sphere };
enum class ShadowFilter { point, bilinear, trilinear };

// A shadowed light. Directional lights fit an orthographic map to what the camera sees
// of the casters (fit_to_view) or around all of them; spot lights a perspective map of
// their outer cone, narrowed to the casters in it; point lights a cube of six maps.
// Every number must be finite; the ranges are given per field.
struct Light {
  std::string name;
  LightType type = LightType::directional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // the way the light travels (normalised here; not zero); not for point
  glm::vec3 position{0.0f};                // spot, point and area lights (their centre)
  float outer_cone_radians = 0.5f;         // spot only: half angle of the cone, in (0, 1.55)
  float range = 0.0f;                      // spot and point: shadows (and light) end there, >= 0; 0: no limit
  // Area lights: a rect `size` wide and high, facing `direction`; a disk or sphere of
  // `radius`; a rect or disk emits both ways when two_sided. Their soft shadows are the
  // mean transmittance over `virtual_lights` (1 to 256) points spread over the light, each
  // with a small map: together they share one map of about `resolution` texels per side
  // (each resolution / ceil(sqrt(virtual_lights)) wide), built as one batch from capture
  // lists (not fixed_memory_build, paged, cascades or clusters).
  glm::vec2 size{1.0f};
  float radius = 0.5f;
  bool two_sided = false;
  uint32_t virtual_lights = 64;  // the scene files' default (scene/light.h says why)
  bool fit_to_view = false;                // directional: fit the map to the Camera's view (fill its forward, up, planes)
  float shadow_distance = 0.0f;            // directional, fit_to_view: how far shadows reach, >= 0 (0: camera far)
  uint32_t cascades = 1;                   // directional with fit_to_view: 1 to 4 maps split along the view; else 1
  // Clustered maps (seed 004): up to this many maps, each fitted to a group of the
  // CasterObjects given to set_lights (0 or 1: off).
  // Directional and spot lights without cascades only.
  uint32_t clusters = 0;
  uint32_t nodes = 8;                      // AVSM nodes per texel: 4, 8, 12 or 16
  uint32_t resolution = 512;               // map texels per side, 1 to 16384
  ShadowFilter filter = ShadowFilter::bilinear;  // trilinear builds and reads mips
  bool sort = true;                        // sort each texel's segments first: the same map every run
  // Build the map straight from the casters, in fixed memory (no capture lists;
  // volumes need their density atlas): see docs/shadows.md, "The fixed-memory build".
  bool fixed_memory_build = false;
  // Paged (docs/shadows.md, "Paged maps"): instead of one map of `resolution`, a virtual
  // map of virtual_resolution^2 texels (a power of two, 256 to 16384; to 262144 for a
  // directional light, whose finest levels keep only the pages around the camera) in pages of
  // page_size^2 (32, 64 or 128) held in a pool of page_pool_mib, of which only the pages
  // the lookups ask for are built, and kept from frame to frame. The shading pass must
  // ask (AVSM_SHADOW_PAGE_REQUESTS_BINDING, ShadowLookupBuffers::page_requests); pages
  // arrive a frame after they are asked for, at most page_builds_per_frame of them per
  // frame (0: no limit; the default keeps a frame whose light moved within 1.5x a dense
  // frame's cost in the engine's default scene: docs/shadows.md). AVSM (or the uncompressed reference) from capture lists only, no cascades or clusters, and
  // directional lights fitted around the casters (not fit_to_view).
  bool paged = false;
  uint32_t virtual_resolution = 16384;
  uint32_t page_size = 64;
  float page_pool_mib = 32.0f;
  uint32_t page_builds_per_frame = 16;
  // What the engine's fog (set_fog) scatters of this light: its colour x intensity, the
  // radiance a white Lambertian surface facing it reflects (docs/embedding.md, "Fog").
  // Spot lights reach it with a hard cone edge. Finite, each component >= 0. The host's
  // own shading is its own.
  glm::vec3 radiance{1.0f};

  bool operator==(const Light&) const = default;
};

// The camera the host shades from; trilinear filtering and paged lights use it (a
// pixel's footprint picks the map's mip level, or the page level it asks for). Every
// number must be finite.
struct Camera {
  glm::vec3 position{0.0f};
  float vertical_fov_radians = 1.0f;  // in (0, pi)
  uint32_t height_pixels = 1;         // at least 1
  // Where it looks: what directional maps fitted to the view (and cascades) follow.
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // not zero
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // not zero, not along forward
  float aspect = 16.0f / 9.0f;           // width / height, > 0
  float near_plane = 0.1f, far_plane = 100.0f;  // 0 < near_plane < far_plane
};

// One light's figures for the frame that finish_frame() closed.
struct LightStats {
  std::string name;
  uint32_t nodes = 0, resolution = 0, mip_levels = 0;
  uint64_t map_bytes = 0;           // the persistent AVSM map
  uint64_t capture_bytes = 0;       // transient capture lists this frame
  uint64_t segments_captured = 0;   // what the casters asked for
  uint64_t segment_capacity = 0;    // what the capture buffer held this frame
  bool overflowed = false;          // segments were dropped: lighter shadows this frame
  bool grew = false;                // the capture buffer grew: the next frame fits
  uint64_t fixed_build_bytes = 0;   // fixed build: its depth image and hair bins this frame
  uint32_t maps = 1;                // point: 6 faces; cascades; clusters
  // Paged lights: pages asked for, resident, built, invalidated, evicted, pending (asked
  // for and served by a coarser level this frame) and the pool's size.
  std::optional<passes::PageStats> pages;
};

// What clustered maps group: one caster's bounds and which draws, strand segments or
// volumes of ShadowCasters it is.
using passes::CasterObject;

// ---------------------------------------------------------------------------------------
// Your command buffer and your descriptor sets: plain Vulkan values, no rendergraph type.
// (Shadows::record() below records a frame; docs/embedding.md, "Your command buffer: record()".)

// Where the host's shader has the lookup's storage buffers (common/shadow_lookup.glsl:
// AVSM_SHADOW_PARAMETERS_BINDING, _ATLAS_, _LIST_HEADS_, _LIST_NODES_BINDING, and
// AVSM_SHADOW_PAGE_REQUESTS_BINDING where the lookups ask for paged maps' pages, in the
// set AVSM_SHADOW_SET). Five distinct numbers of one set; a shader without the page
// requests leaves its binding unused.
struct ShadowLookupBindings {
  uint32_t parameters = 0, atlas = 1, list_heads = 2, list_nodes = 3, page_requests = 4;
  // first .. first + 3: what #define AVSM_SHADOW_BINDING first means; the page requests
  // at first + 4 (#define AVSM_SHADOW_PAGE_REQUESTS_BINDING to it).
  static ShadowLookupBindings consecutive(uint32_t first) {
    return {first, first + 1, first + 2, first + 3, first + 4};
  }
};

// The entries the lookup needs in the host's VkDescriptorSetLayout (ordinary or push
// descriptor): at each of `bindings`, one VK_DESCRIPTOR_TYPE_STORAGE_BUFFER visible to
// `stages` (the stages of the shaders that include the lookup), no immutable samplers.
// std::invalid_argument when two bindings share a number or `stages` is 0.
std::array<VkDescriptorSetLayoutBinding, 5> shadow_lookup_layout(const ShadowLookupBindings& bindings,
                                                                 VkShaderStageFlags stages);

// What the host writes at those bindings: the lookup's buffer ranges (offset and size
// as the lookup gives them; unused_buffer whole where a range is absent).
// They change when lights change and from one frame slot to the next, so write them
// after every record() (into the set of that frame slot).
// page_requests: the paged lights' request bits, cleared by the frame's shadow work;
// the lookups that ask for pages write them, and finish_frame() reads them on the CPU.
// After those lookups the host makes their writes visible to the host (a barrier from
// their stages' SHADER_STORAGE_WRITE to HOST / HOST_READ) before the frame's fence.
struct ShadowLookupBuffers {
  VkDescriptorBufferInfo parameters{}, atlas{}, list_heads{}, list_nodes{}, page_requests{};
  // The fog's two storage buffers (set_fog; shaders/common/fog.glsl's AVSM_FOG_BINDING and
  // AVSM_FOG_INTEGRATED_BINDING), from record(): the host writes them where its composite
  // has them (not among writes() below). Empty from lookup_buffers().
  VkDescriptorBufferInfo fog_parameters{}, fog_grid{};
  // Five STORAGE_BUFFER writes into `set` at `bindings`, for vkUpdateDescriptorSets (or
  // vkCmdPushDescriptorSetKHR, which ignores dstSet). They point into this object: keep
  // it alive until the call.
  std::array<VkWriteDescriptorSet, 5> writes(VkDescriptorSet set, const ShadowLookupBindings& bindings) const;
};

// The buffers to write for `lookup` (a pass list's, or Shadows::unshadowed_lookup()).
ShadowLookupBuffers lookup_buffers(const ShadowLookupResources& lookup);

// A pipeline stage and access scope, as VkDependencyInfo takes them.
struct AccessScope {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// One frame for Shadows::record().
struct ShadowFrame {
  Camera camera;
  ShadowCasters casters;  // the host's buffers, as pass_list takes them (same preconditions)
  uint32_t frame_slot = 0;
  // The host's writes to the casters' buffers (and the volume atlas) earlier in this queue
  // that no barrier or fence has yet made visible: record() begins with a barrier from
  // this scope. NONE (the default) when they are already visible, e.g. written through a
  // mapped pointer before the submission, or uploaded in a submission the host waited for.
  AccessScope casters_written;
  // The shader stages in which the host reads the lookup buffers (storage reads, in `cmd`
  // after record() or in later submissions on the queue): record() ends with a barrier
  // that makes the frame's shadows visible there, and begins with one that waits for the
  // previous frame's reads there. Not 0.
  VkPipelineStageFlags2 lookup_read_stages = VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT |
                                             VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
};

class Shadows {
 public:

  // Pipelines are built here, from `shaders`, on `context` (owned or adopted; it must
  // outlive this). The shaders' folder (glsl_root/shaders with compile_from_source, else
  // spirv_root/shaders) must exist: std::invalid_argument otherwise.
  Shadows(gpu::Context& context, const ShaderLocation& shaders);
  ~Shadows();
  Shadows(const Shadows&) = delete;
  Shadows& operator=(const Shadows&) = delete;

  // The lights that cast (any number; all maps share one buffer of at most the device's
  // storage buffer range), their maps fitted around `casters_bounds` (everything that
  // casts or receives). Light i is light_index i in the shader. `objects` are what
  // lights with clusters group. Preconditions (check_lights): each light as Light
  // documents; `casters_bounds` empty (a unit box at the origin) or finite with min <=
  // max; each object's bounds likewise, its count at least 1 and its range within the
  // casters later given to pass_list (checked there). Throws std::invalid_argument
  // for a violation and for maps over the budget, naming the lights; nothing changes then.
  // Lights that only moved (the same lights and casters_bounds as before, only their
  // position and direction changed; none clustered) are placed for the next frame
  // declared, without waiting for the frames in flight: call it every frame to move
  // them. Any other change makes the maps' buffers again: it waits for the device to
  // idle, and the host finishes its frames in flight (finish_frame) before it.
  void set_lights(const std::vector<Light>& lights, const Bounds& casters_bounds,
                  const std::vector<CasterObject>& objects = {});
  void set_light(const Light& light, const Bounds& casters_bounds) { set_lights({light}, casters_bounds); }

  // Frames the host records ahead of the GPU, 1 to 3 (1 until set): each frame is then
  // declared into a frame slot 0..count-1 (pass_list, finish_frame), which has its
  // own parameter block and capture counters. The host records into slot s again only
  // after the frame it last held completed (its fence; one executor per slot, as the
  // executor's transients belong to the frame it recorded), and finishes frames in the
  // order it declared them. Waits for the device to idle; std::invalid_argument for
  // another count.
  void set_frames_in_flight(uint32_t count);

  // Describes this frame's passes for every light (capture, sort, resolve, mips) into
  // frame slot `frame_slot`, without recording anything: the ordered passes, the
  // resources they use and how, and their record functions (passes/shadows/shadow_pass_list.h);
  // `lookup` is what the host's shading passes read and bind. The list is the frame's
  // whole description: avsm::add_to_graph (avsm/shadows_rendergraph.h) declares it into
  // the engine's graph. Record it before this slot's finish_frame(). The casters' buffers
  // must stay alive and unchanged until the frame completes.
  // Preconditions (check_frame; std::invalid_argument, nothing described):
  //   - frame_slot is below the frames in flight;
  //   - camera: as Camera documents;
  //   - every view with something to cast (draws, segment_count, volume_count) has its
  //     buffers (not VK_NULL_HANDLE), each with a size that is a whole, non-zero number
  //     of its elements (CasterVertex, uint32 index, vec4 point, StrandSegment,
  //     StrandParameters, GpuVolume: the layouts are fixed, there is no stride to set);
  //   - meshes: each draw's indices [first_index, first_index + index_count) lie in the
  //     index buffer, index_count is a multiple of 3, vertex_offset is below the vertex
  //     count, alpha is one of CasterAlpha, alpha_cutoff and alpha_factor are in [0, 1];
  //   - strands: segments [first_segment, first_segment + segment_count) lie in the
  //     segment buffer; at least 2 points and 1 strand;
  //   - volumes: volume_count GpuVolume in the parameter buffer; grids and majorants
  //     given; the density atlas whole (atlas, atlas_sampler and brick_slots) or absent;
  //   - the CasterObjects given to set_lights lie within these casters.
  ShadowPassList pass_list(const Camera& camera, const ShadowCasters& casters, uint32_t frame_slot = 0);

  // After the frame declared into `frame_slot` completed: reads its capture counters and
  // grows an overflowed capture buffer for the next frame declared. Precondition (the
  // host's to keep, it cannot be checked here): that frame's work has finished on the GPU.
  std::vector<LightStats> finish_frame(uint32_t frame_slot = 0);

  // Buffers that leave every light unshadowed (for a pass drawn without maps): no
  // resources to read, only buffers to bind.
  ShadowLookupResources unshadowed_lookup() const;

  // The engine's fog (scene/fog.h; content/README.md, "fog"): a global medium and fog
  // boxes, lit by every light (Light::radiance, and the uniform sky scaled by
  // fog.sky_light) through the lights' maps, reaching fog.grid.distance from the camera or
  // else the far side of set_lights' casters_bounds. While it is set and on, each pass list
  // ends with its two passes ("fog scattering", into a transient 3D image of
  // fog.grid.froxel_pixels and slices; "fog integration", into a buffer of the frame
  // slot's) and its `fog` says what the host's composite binds. Preconditions (std::
  // invalid_argument naming the field, nothing changed): every number finite; scattering
  // and absorption 0 to 100 per metre, phase_g -0.95 to 0.95, colours in [0, 1], sky_light
  // 0 to 4, froxel_pixels 4 to 64, slices 8 to 256, distance >= 0, each box's min below its
  // max. A fog with no medium is no fog.
  void set_fog(const Fog& fog);
  // Off: no fog passes, the settings kept (on until set otherwise).
  void set_fog_enabled(bool enabled);

  // ---- Your command buffer (no rendergraph type; docs/embedding.md, "Your command buffer: record()").
  // Records the frame's shadow work (every light's capture, sort, build and mips, with the
  // barriers between them) into `cmd`, and returns the buffers the host's lookup binds.
  //   - cmd: a primary command buffer in the recording state, outside any render pass, for
  //     the queue family the Context was given (graphics + compute), submitted on that queue.
  //   - inputs: the casters' buffers written before the submission, or in `cmd` earlier
  //     within frame.casters_written; the volume atlas (if any) in SHADER_READ_ONLY_OPTIMAL.
  //     They must stay alive and unchanged until the frame completes.
  //   - outputs: the four lookup buffers (ShadowLookupBuffers), left visible to storage
  //     reads (VK_ACCESS_2_SHADER_STORAGE_READ_BIT) in frame.lookup_read_stages; the host
  //     reads them there and never writes them. The next record() waits for those reads.
  //   - frame slots: as pass_list's; call finish_frame(frame_slot) after the frame has
  //     completed, and record into that slot again only then.
  // Transient memory (capture lists, the fixed build's depth image and hair bins) comes
  // from the library, kept per frame slot and reused while the frame's shape is unchanged.
  // std::invalid_argument naming "avsm::Shadows::record" and the argument for a null cmd,
  // a casters_written with access but no stages, no lookup_read_stages, and pass_list's
  // preconditions; nothing is recorded then.
  ShadowLookupBuffers record(VkCommandBuffer cmd, const ShadowFrame& frame);

  const ShaderLocation& shader_location() const;
  // Include directories for a host shader that uses the lookup (the engine's GLSL, NanoVDB).
  std::vector<std::filesystem::path> glsl_include_dirs() const;
  // Compiles a host GLSL file (.vert .frag .comp .geom) with those include directories;
  // throws gpu::ShaderCompileError with the file and line of the first error.
  std::vector<uint32_t> compile_glsl(const std::filesystem::path& file) const;

  // The preconditions of set_lights() and pass_list() on their own: no device needed,
  // so a host can validate its data up front (and tests can). Throw std::invalid_argument
  // naming the function they guard ("avsm::Shadows::set_lights: light 1 'key': ...").
  // Settings that depend on the device (the maps' budget) are checked by set_lights only.
  static void check_lights(const std::vector<Light>& lights, const Bounds& casters_bounds,
                           const std::vector<CasterObject>& objects = {});
  static void check_frame(const Camera& camera, const ShadowCasters& casters,
                          const std::vector<CasterObject>& objects = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  // record()'s executors, one per frame slot, made on first use (shadows_record.cpp). A
  // shared_ptr, whose deleter is bound where Recorder is complete (not in shadows.cpp).
  struct Recorder;
  static std::shared_ptr<Recorder> make_recorder(gpu::Context& context);
  std::shared_ptr<Recorder> recorder_;
};

#if defined(AVSM_PACKAGE_GLSL_ROOT) && defined(AVSM_PACKAGE_SPIRV_ROOT)
inline ShaderLocation ShaderLocation::of_package() { return {AVSM_PACKAGE_GLSL_ROOT, AVSM_PACKAGE_SPIRV_ROOT}; }
#endif

}  // namespace avsm
