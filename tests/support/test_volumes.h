#pragma once
// Procedural OpenVDB volumes for GPU pass tests, loaded the way scenes load them.
#include <openvdb/openvdb.h>

#include "scene/volume.h"

namespace avsm::testing {

// A grid of constant density over voxels [lo, hi] (inclusive), with a linear transform.
openvdb::FloatGrid::Ptr constant_box_grid(const openvdb::Coord& lo, const openvdb::Coord& hi, float density,
                                          float voxel_size);

// Writes `grid` to a temporary VDB file and loads it with scene::load_vdb_volume.
scene::Volume load_grid(openvdb::FloatGrid::Ptr grid, const scene::VolumeOptions& options);

}  // namespace avsm::testing
