#include "support/test_volumes.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace avsm::testing {

openvdb::FloatGrid::Ptr constant_box_grid(const openvdb::Coord& lo, const openvdb::Coord& hi, float density,
                                          float voxel_size) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel_size));
  grid->fill(openvdb::CoordBBox(lo, hi), density, true);
  return grid;
}

scene::Volume load_grid(openvdb::FloatGrid::Ptr grid, const scene::VolumeOptions& options) {
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
