// OpenVDB side of volume loading: read, check, measure, convert to NanoVDB.
// The only translation unit of avsm_scene that includes OpenVDB (slow to compile).
#include "scene/volume.h"

#include "scene/load_error.h"
#include "scene/vdb_layout.h"
#include "scene/volume_sequence.h"

#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>

namespace avsm::scene {
namespace {

constexpr std::uint64_t kMaxMajorantBricks = 1ull << 26;

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string grid_name_of(const detail::VdbGridRecord& record) {
  return record.unique_name.substr(0, record.unique_name.find('\x1e'));  // OpenVDB's duplicate-name suffix
}

// Checks the file's framing before OpenVDB sees it (see vdb_layout.h) and that
// the grid we want is there and holds floats.
void check_vdb_file(const std::filesystem::path& file, const std::string& grid_name, std::uint64_t max_bytes) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (error || !std::filesystem::exists(status)) throw LoadError(file, "file not found");
  if (!std::filesystem::is_regular_file(status)) throw LoadError(file, "not a regular file");
  const std::uint64_t size = std::filesystem::file_size(file, error);
  if (size > max_bytes) throw LoadError(file, "file is larger than the limit of " + std::to_string(max_bytes) + " bytes");
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw LoadError(file, "cannot open it for reading");
  const detail::VdbLayout layout = detail::read_vdb_layout(stream, size, file);

  std::string names;
  for (const detail::VdbGridRecord& record : layout.grids) {
    if (grid_name_of(record) == grid_name) {
      if (record.type.rfind("Tree_float_", 0) != 0)
        throw LoadError(file, "grid '" + grid_name + "' holds " + record.type + " values, not float density");
      return;
    }
    names += (names.empty() ? "'" : ", '") + grid_name_of(record) + "'";
  }
  throw LoadError(file, "no grid named '" + grid_name + "' (grids in the file: " + (names.empty() ? "none" : names) + ")");
}

// OpenVDB writes the active voxel count it saved as metadata; a mismatch means
// the topology did not survive the trip.
void check_saved_voxel_count(const openvdb::FloatGrid& grid, const std::filesystem::path& file) {
  const auto saved = grid.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_VOXEL_COUNT);
  if (saved && std::uint64_t(saved->value()) != grid.activeVoxelCount())
    throw LoadError(file, "grid '" + grid.getName() + "' has " + std::to_string(grid.activeVoxelCount()) +
                              " active voxels but the file says it saved " + std::to_string(saved->value()));
}

openvdb::FloatGrid::Ptr read_float_grid(const std::filesystem::path& file, const std::string& grid_name) {
  openvdb::GridBase::Ptr base;
  try {
    openvdb::io::File vdb(file.string());
    vdb.open(/*delayLoad=*/false);  // read now: no lazy mmap reads that could fail later
    if (!vdb.hasGrid(grid_name)) throw LoadError(file, "OpenVDB does not find grid '" + grid_name + "'");
    base = vdb.readGrid(grid_name);
    vdb.close();
  } catch (const LoadError&) {
    throw;
  } catch (const std::exception& error) {
    throw LoadError(file, std::string("OpenVDB cannot read it: ") + error.what());
  }
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
  const std::string label = "grid '" + grid_name + "'";
  if (!grid) throw LoadError(file, label + " holds " + base->valueType() + " values, not float density");
  if (grid->getGridClass() == openvdb::GRID_LEVEL_SET)
    throw LoadError(file, label + " is a level set (signed distances), not a fog volume");
  if (grid->background() != 0.0f)
    throw LoadError(file, label + " has background " + std::to_string(grid->background()) +
                              "; a fog volume needs 0 outside its active voxels");
  if (!grid->transform().isLinear()) throw LoadError(file, label + " has a non-linear (frustum) transform");
  check_saved_voxel_count(*grid, file);
  return grid;
}

glm::dmat4 to_glm(const openvdb::math::Mat4d& m) {
  // OpenVDB multiplies row vectors (v * M, translation in the last row); glm
  // multiplies column vectors with column-major storage, so the element order
  // is the same: glm[i][j] = M(i, j).
  glm::dmat4 result;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) result[i][j] = m(i, j);
  return result;
}

void set_mapping(Volume& volume, const openvdb::FloatGrid& grid, const std::filesystem::path& file) {
  const glm::dmat4 vdb_world_from_index = to_glm(grid.transform().baseMap()->getAffineMap()->getMat4());
  const glm::dmat4 world_from_index = glm::dmat4(volume.transform) * vdb_world_from_index;
  const double det = glm::determinant(glm::dmat3(world_from_index));
  if (!std::isfinite(det) || std::abs(det) < 1e-30)
    throw LoadError(file, "grid transform combined with the placement is singular or not finite");
  volume.world_from_index = glm::mat4(world_from_index);
  volume.index_from_world = glm::mat4(glm::inverse(world_from_index));
}

int ceil_div(int a, int b) { return (a + b - 1) / b; }
int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

void setup_majorant(Volume& volume, int brick_size, const std::filesystem::path& file) {
  MajorantGrid& m = volume.majorant;
  m.brick_size = brick_size;
  m.index_origin = volume.active_index_min - 1;  // trilinear support starts one voxel out
  const glm::ivec3 extent = volume.active_index_max + 1 - m.index_origin;
  m.dims = glm::ivec3(ceil_div(extent.x, brick_size), ceil_div(extent.y, brick_size), ceil_div(extent.z, brick_size));
  const std::uint64_t bricks = std::uint64_t(m.dims.x) * m.dims.y * m.dims.z;
  if (bricks > kMaxMajorantBricks)
    throw LoadError(file, "active region needs " + std::to_string(bricks) + " majorant bricks of " +
                              std::to_string(brick_size) + "^3 voxels; use larger bricks");
  m.max_density.assign(bricks, 0.0f);
  volume.world_from_majorant = volume.world_from_index *
                               glm::translate(glm::mat4(1.0f), glm::vec3(m.index_origin)) *
                               glm::scale(glm::mat4(1.0f), glm::vec3(float(brick_size)));
}

// Raises the majorant of every brick that voxels lo..hi (inclusive, one value)
// can influence: voxel v reaches index positions in (v - 1, v + 1).
void raise_majorant(MajorantGrid& m, const glm::ivec3& lo, const glm::ivec3& hi, float value) {
  glm::ivec3 first, last;
  for (int axis = 0; axis < 3; ++axis) {
    first[axis] = std::max(0, floor_div(lo[axis] - m.index_origin[axis] - 1, m.brick_size));
    last[axis] = std::min(m.dims[axis] - 1, ceil_div(hi[axis] - m.index_origin[axis] + 1, m.brick_size) - 1);
  }
  for (int z = first.z; z <= last.z; ++z)
    for (int y = first.y; y <= last.y; ++y)
      for (int x = first.x; x <= last.x; ++x) {
        float& slot = m.max_density[std::size_t(x) + std::size_t(m.dims.x) * (std::size_t(y) + std::size_t(m.dims.y) * z)];
        slot = std::max(slot, value);
      }
}

// One pass over the active values (voxels and tiles): statistics, majorants,
// and the check that every value is finite.
void measure(Volume& volume, const openvdb::FloatGrid& grid, const std::filesystem::path& file) {
  DensityStats& stats = volume.stats;
  stats.min = std::numeric_limits<float>::infinity();
  stats.max = -std::numeric_limits<float>::infinity();
  double sum = 0.0;
  for (auto value = grid.cbeginValueOn(); value; ++value) {
    const float density = *value;
    const openvdb::CoordBBox box = value.getBoundingBox();
    if (!std::isfinite(density)) {
      std::ostringstream where;
      where << box.min();
      throw LoadError(file, "grid '" + volume.grid_name + "' holds a non-finite value at voxel " + where.str());
    }
    const std::uint64_t count = value.getVoxelCount();
    stats.min = std::min(stats.min, density);
    stats.max = std::max(stats.max, density);
    sum += double(density) * double(count);
    stats.active_voxel_count += count;
    raise_majorant(volume.majorant, glm::ivec3(box.min().x(), box.min().y(), box.min().z()),
                   glm::ivec3(box.max().x(), box.max().y(), box.max().z()), std::max(density, 0.0f));
  }
  stats.mean = sum / double(stats.active_voxel_count);
}

void convert_to_nanovdb(Volume& volume, const openvdb::FloatGrid& grid, const std::filesystem::path& file) {
  auto handle = nanovdb::openToNanoVDB(grid);
  const auto* nano = handle.grid<float>();
  if (nano == nullptr || !nano->isValid()) throw LoadError(file, "conversion to NanoVDB failed");
  const auto* bytes = reinterpret_cast<const std::byte*>(handle.data());
  volume.nanovdb.assign(bytes, bytes + handle.size());
}

}  // namespace

const char* to_string(VolumeShading::Mode mode) {
  switch (mode) {
    case VolumeShading::Mode::fast: return "fast";
    case VolumeShading::Mode::reference: return "reference";
    case VolumeShading::Mode::hidden: return "hidden";
  }
  return "?";
}

std::optional<VolumeShading::Mode> volume_shading_mode_from_string(const std::string& name) {
  if (name == "fast") return VolumeShading::Mode::fast;
  if (name == "reference") return VolumeShading::Mode::reference;
  if (name == "hidden") return VolumeShading::Mode::hidden;
  return std::nullopt;
}

Volume load_vdb_volume(const std::filesystem::path& file, const VolumeOptions& options) {
  if (options.majorant_brick_size < 2 || options.majorant_brick_size > 64)
    throw LoadError(file, "majorant brick size " + std::to_string(options.majorant_brick_size) + " is outside 2 to 64");
  check_vdb_file(file, options.grid_name, options.max_file_bytes);
  initialize_openvdb();
  const openvdb::FloatGrid::Ptr grid = read_float_grid(file, options.grid_name);

  Volume volume;
  volume.name = file.stem().string();
  volume.grid_name = options.grid_name;
  volume.transform = options.transform;
  volume.extinction_scale = options.extinction_scale;
  volume.albedo = options.albedo;
  set_mapping(volume, *grid, file);

  const openvdb::CoordBBox active = grid->evalActiveVoxelBoundingBox();
  if (active.empty()) throw LoadError(file, "grid '" + options.grid_name + "' has no active voxels");
  volume.active_index_min = glm::ivec3(active.min().x(), active.min().y(), active.min().z());
  volume.active_index_max = glm::ivec3(active.max().x(), active.max().y(), active.max().z());
  const Bounds support{glm::vec3(volume.active_index_min - 1), glm::vec3(volume.active_index_max + 1)};
  volume.world_bounds = transform_bounds(support, volume.world_from_index);

  setup_majorant(volume, options.majorant_brick_size, file);
  measure(volume, *grid, file);
  convert_to_nanovdb(volume, *grid, file);
  return volume;
}

Bounds read_vdb_bounds(const std::filesystem::path& file, const VolumeOptions& options) {
  check_vdb_file(file, options.grid_name, options.max_file_bytes);
  initialize_openvdb();
  openvdb::GridBase::Ptr header;
  try {
    openvdb::io::File vdb(file.string());
    vdb.open(/*delayLoad=*/true);
    header = vdb.readGridMetadata(options.grid_name);
    vdb.close();
  } catch (const std::exception& error) {
    throw LoadError(file, std::string("OpenVDB cannot read its grid header: ") + error.what());
  }
  const auto min = header->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
  const auto max = header->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
  if (!min || !max) {  // written without its box: read the voxels
    VolumeOptions whole = options;
    return load_vdb_volume(file, whole).world_bounds;
  }
  if (!header->transform().isLinear()) throw LoadError(file, "grid '" + options.grid_name + "' has a non-linear (frustum) transform");
  // As set_mapping() computes it, so that the frame's own bounds come out the same.
  const glm::mat4 world_from_index(glm::dmat4(options.transform) *
                                   to_glm(header->transform().baseMap()->getAffineMap()->getMat4()));
  const openvdb::Vec3i lo = min->value(), hi = max->value();
  const Bounds support{glm::vec3(lo.x() - 1, lo.y() - 1, lo.z() - 1), glm::vec3(hi.x() + 1, hi.y() + 1, hi.z() + 1)};
  return transform_bounds(support, world_from_index);
}

}  // namespace avsm::scene
