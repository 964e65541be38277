#pragma once
// Procedural volumes for GPU pass tests, loaded the way scenes load them (from a VDB file).
// OpenVDB stays inside test_volumes.cpp: its headers cost a test file 10-20 s to compile.
#include <glm/glm.hpp>
#include <vector>

#include "scene/volume.h"

namespace avsm::testing {

// Voxels [lo, hi] (inclusive) of one density.
struct VoxelBox {
  glm::ivec3 lo{0}, hi{0};
  float density = 1.0f;
};

// A density grid of `boxes` (a later box overwrites an earlier one where they overlap)
// with voxels `voxel_size` wide, written to a temporary VDB file and loaded with
// scene::load_vdb_volume.
scene::Volume load_box_volume(const std::vector<VoxelBox>& boxes, float voxel_size,
                              const scene::VolumeOptions& options);

}  // namespace avsm::testing
