#include "support/test_volumes.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace avsm::testing {

scene::Volume load_box_volume(const std::vector<VoxelBox>& boxes, float voxel_size,
                              const scene::VolumeOptions& options) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  for (const VoxelBox& box : boxes)
    grid->fill(openvdb::CoordBBox(openvdb::Coord(box.lo.x, box.lo.y, box.lo.z), openvdb::Coord(box.hi.x, box.hi.y, box.hi.z)),
               box.density, true);
  // One file per test and process, so parallel test runs do not collide.
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("avsm_test_" + std::string(info ? info->name() : "volume") + "_" +
                                      std::to_string(::getpid()) + ".vdb");
  {
    openvdb::io::File vdb(file.string());
    vdb.write({grid});
    vdb.close();
  }
  scene::Volume volume = scene::load_vdb_volume(file, options);
  std::filesystem::remove(file);
  return volume;
}

}  // namespace avsm::testing
