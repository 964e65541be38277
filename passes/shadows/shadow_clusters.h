#pragma once
// Clustered shadow maps (seed 004, "clustered deep shadow maps"): a light's casters
// grouped by their light-space bounds, so that a sparse scene (plumes far apart) gets a
// map fitted tightly to each group instead of one map mostly made of empty space. A
// receiver's transmittance is the product over the clusters' maps.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/bounds.h"
#include "scene/light.h"

namespace avsm::scene {
struct Scene;
}

namespace avsm::passes {

// One caster clusters group: its world bounds and which of the frame's ShadowCasters it is.
struct CasterObject {
  enum class Kind { mesh_draw, strands, volume } kind = Kind::mesh_draw;
  uint32_t first = 0, count = 1;  // mesh draws, strand segments or volumes [first, first + count)
  scene::Bounds bounds;
  std::string name;
};

// The casters of a loaded scene in the order the camera passes hand them to the shadow
// maps (OpaquePass::casters(), HairPass::casters(), VolumePass::casters()).
std::vector<CasterObject> scene_caster_objects(const scene::Scene& scene);
// Per scene mesh, the index of its object among scene_caster_objects(), or
// kNoCasterObject for a mesh without triangles (it casts nothing).
inline constexpr uint32_t kNoCasterObject = ~0u;
std::vector<uint32_t> mesh_caster_objects(const scene::Scene& scene);

struct CasterCluster {
  std::vector<uint32_t> objects;  // indices into the objects given
  scene::Bounds bounds;           // world bounds of them all
};

// Volumes a cluster can select (VolumeCasters::volume_mask has a bit per volume):
// scenes with more are not clustered.
inline constexpr uint32_t kMaxClusteredVolumes = 32;

// Groups `objects` into at most `max_clusters` clusters by the distance of seed 004
// (eq. 2: the largest difference of their light-space extents' corners), merging the
// closest clusters (complete linkage) while there are too many or while two are closer
// than a quarter of the smaller one's extent. Light space: the directional light's
// orthographic plane, or the spot light's view-plane tangents.
std::vector<CasterCluster> cluster_casters(const scene::Light& light, const std::vector<CasterObject>& objects,
                                           uint32_t max_clusters);

}  // namespace avsm::passes
