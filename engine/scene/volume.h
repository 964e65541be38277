#pragma once
// Fog volumes: an OpenVDB float grid converted to one NanoVDB buffer for the
// GPU (sampled there through PNanoVDB.h), plus what a renderer needs around it:
// world mapping, bounds, a coarse majorant grid for empty-space skipping,
// density statistics, and CPU reference sampling / transmittance.
#include "scene/bounds.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <vector>

namespace avsm::scene {

// NanoVDB grids must start on a 32-byte boundary (NANOVDB_DATA_ALIGNMENT).
template <class T, std::size_t Alignment>
struct AlignedAllocator {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = AlignedAllocator<U, Alignment>;
  };
  AlignedAllocator() = default;
  template <class U>
  AlignedAllocator(const AlignedAllocator<U, Alignment>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(Alignment))); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(Alignment)); }
  template <class U>
  bool operator==(const AlignedAllocator<U, Alignment>&) const { return true; }
};
using NanoVdbBytes = std::vector<std::byte, AlignedAllocator<std::byte, 32>>;

struct DensityStats {
  float min = 0.0f;  // over active voxels (tiles count with their voxels)
  float max = 0.0f;
  double mean = 0.0;
  std::uint64_t active_voxel_count = 0;
};

// One value per brick of brick_size^3 voxels: an upper bound of the trilinear
// density anywhere inside the brick (it includes the voxels one step outside,
// since trilinear interpolation reads them). Zero means "skip this brick".
// Brick b covers index space [index_origin + b * brick_size, ... + brick_size].
struct MajorantGrid {
  glm::ivec3 dims{0};
  int brick_size = 8;
  glm::ivec3 index_origin{0};
  std::vector<float> max_density;  // x fastest, then y, then z

  float at(const glm::ivec3& brick) const {
    return max_density[std::size_t(brick.x) + std::size_t(dims.x) * (std::size_t(brick.y) + std::size_t(dims.y) * brick.z)];
  }
};

// How the camera sees fog volumes (scene file "volume_shading"; avsm-capture
// --volume-shading, --volume-resolution-divisor, --volume-step).
struct VolumeShading {
  enum class Mode {
    fast,       // lighting cache, brick-atlas density, reduced-resolution march, per-vertex hair lighting
    reference,  // full resolution, quarter-voxel NanoVDB steps, shadow lookups along every ray
    hidden,     // the camera does not see the volumes (they still cast shadows): comparisons, masks
  };
  Mode mode = Mode::fast;
  int resolution_divisor = 2;  // fast: the march runs at 1/divisor of the output per axis (1, 2 or 4)
  // fast: march step in voxels (of the smallest voxel edge). 2: the image error against
  // step size (bench/frame) stays flat up to 2 and grows beyond, for little time saved.
  float step_voxels = 2.0f;
};
const char* to_string(VolumeShading::Mode mode);
std::optional<VolumeShading::Mode> volume_shading_mode_from_string(const std::string& name);

// What avsm-capture's and the viewer's flags change of a scene's VolumeShading.
struct VolumeShadingOverrides {
  std::optional<VolumeShading::Mode> mode;
  std::optional<int> resolution_divisor;
  std::optional<float> step_voxels;

  bool operator==(const VolumeShadingOverrides&) const = default;
  void apply(VolumeShading& shading) const {
    if (mode) shading.mode = *mode;
    if (resolution_divisor) shading.resolution_divisor = *resolution_divisor;
    if (step_voxels) shading.step_voxels = *step_voxels;
  }
};

// Light scattered more than once inside a volume, approximated by octaves of single
// scattering (Wrenninge, Zafar, Clifford et al., "Oz: The Great and Volumetric", 2013):
// octave k sees the optical depth towards each light (and the sky) scaled by
// attenuation^k and carries (contribution * albedo * (1 - escape))^k of its light, so
// light reaches deeper into the medium and a dense, bright one turns white where lit.
// escape is the chance that light scattered at the point leaves the volume before it
// scatters again (the mean transmittance over the sphere: scene::sky_lighting), so
// thin smoke gains little, and the albedo keeps dark smoke dark.
// The phase function is isotropic (shaders/common/volume.glsl), so the method's
// eccentricity term has nothing to act on. octaves 1: single scattering only.
struct MultipleScattering {
  int octaves = 4;             // 1 to 8 (scene file "multiple_scattering": {"octaves": N})
  float attenuation = 0.5f;    // (0, 1]: the optical depth octave k sees, per octave
  float contribution = 0.9f;   // [0, 1]: the light octave k carries, per octave, before albedo and escape
  bool operator==(const MultipleScattering&) const = default;
};

struct Volume {
  std::string name;
  std::string grid_name;
  NanoVdbBytes nanovdb;             // one NanoVDB float grid: upload as is
  // Scene world <-> NanoVDB index space; voxel centres sit at integer index
  // coordinates (OpenVDB's convention), so trilinear filtering at index
  // position p blends the voxels floor(p) and floor(p) + 1.
  glm::mat4 world_from_index{1.0f};
  glm::mat4 index_from_world{1.0f};
  glm::ivec3 active_index_min{0};   // inclusive bounding box of the active voxels
  glm::ivec3 active_index_max{-1};
  Bounds world_bounds;              // where the trilinear density can be non-zero
  MajorantGrid majorant;
  DensityStats stats;
  float extinction_scale = 1.0f;    // sigma_t = extinction_scale * density, per world unit
  glm::vec3 albedo{1.0f};           // sigma_s = albedo * sigma_t
  glm::mat4 transform{1.0f};        // the placement applied: scene world from VDB world
  glm::mat4 world_from_majorant{1.0f};  // brick coordinates (brick units) to scene world
  // Lighting cache cells per axis are the support's voxels / at least this (scene file
  // "lighting_cache": {"downsample": N}); more when the volume is small on screen.
  float lighting_cache_downsample = 2.0f;
  // "lighting_cache": "off": the fast march looks every light's map up along the ray
  // inside this volume instead (exact lighting, the reference's cost).
  bool lighting_cache = true;
  MultipleScattering multiple_scattering;  // scene file "multiple_scattering" ("off": octaves 1)
  // The sky's light (kSkyAmbient, as surfaces and hair get it) scattered in the volume,
  // shadowed by the volume itself, times this (scene file "sky_light"; 0: none).
  float sky_light = 1.0f;

  float max_extinction() const { return extinction_scale * stats.max; }
  // The shortest voxel edge in scene world units: the marches step by fractions of it.
  float smallest_voxel_edge() const {
    const glm::mat3 linear(world_from_index);
    return std::min({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
  }
};

struct VolumeOptions {
  std::string grid_name = "density";
  glm::mat4 transform{1.0f};
  float extinction_scale = 1.0f;
  glm::vec3 albedo{1.0f};
  int majorant_brick_size = 8;       // 2 to 64 voxels
  std::uint64_t max_file_bytes = 1ull << 33;
};

// Reads the float fog grid `grid_name` from an OpenVDB file. Throws LoadError
// (naming the file) for a missing/unreadable file, a file that is not VDB, a
// missing grid (listing those present), a grid that is not float, a level set,
// a non-zero background, a non-affine transform, non-finite values, or no
// active voxels.
Volume load_vdb_volume(const std::filesystem::path& file, const VolumeOptions& options = {});

// ---- CPU reference (tests compare GPU results against these) ----

// Trilinear density at a world point (0 outside the active region), read
// through NanoVDB's own sampler from Volume::nanovdb. Thread-safe.
float sample_density(const Volume& volume, const glm::vec3& world);

// sigma_t integrated along the segment from -> to: extinction_scale times the
// integral of max(density, 0), midpoint rule with at most `step` world units
// per sample (default: a quarter voxel). Bricks with a zero majorant are skipped.
float optical_depth(const Volume& volume, const glm::vec3& from, const glm::vec3& to, float step = 0.0f);

// exp(-optical_depth): the fraction of light that survives the segment.
float transmittance(const Volume& volume, const glm::vec3& from, const glm::vec3& to, float step = 0.0f);

}  // namespace avsm::scene
