#pragma once
// The scene file's "animation" blocks (content/README.md, "Animation"), read as the rest
// of the file is: strictly, every error naming the JSON path. Internal to description.cpp.
#include "scene/animation.h"
#include "scene/json_reader.h"

namespace avsm::scene::detail {

// A camera entry's "animation": keys for position, target, up and vertical_fov_deg.
CameraTracks read_camera_animation(ObjectReader& camera);
// A light entry's "animation": keys for position (spot, point and area lights) and
// direction or target (lights that point). `light` is the entry as read; a light aimed
// at a static target keeps aiming at it while its position moves.
LightTracks read_light_animation(ObjectReader& entry, const Light& light);
// A model entry's "animation": keys for translation, rotation_deg and scale, on top of
// its "transform", which must then be of that form (not "matrix").
TransformTracks read_model_animation(ObjectReader& model);

}  // namespace avsm::scene::detail
