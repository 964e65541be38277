#pragma once
// What lies under a pixel (the viewer's texel inspector, the capture's flicker probes): a CPU ray cast from the camera through the pixel centre
// against the scene's meshes (the opaque surfaces the frame shows), else into the
// fog volumes (the middle of the ray's stretch inside the first volume's bounds).
// Hair is not hit: strands are thinner than a pixel and the volume or the surface
// behind them is what the light ray through that pixel mostly crosses.
#include <glm/glm.hpp>

#include <optional>
#include <string>

#include "passes/frame/view.h"
#include "scene/scene.h"

namespace avsm::renderer {

struct PickedPoint {
  glm::vec3 world{0.0f};
  std::string what;        // "mesh 'floor'", "volume 'smoke'"
  glm::vec3 normal{0.0f};  // a mesh's: its triangle's, facing the camera; zero in a volume
};

// `pixel`: x right, y down from the top-left corner of the view's image, in pixels.
std::optional<PickedPoint> pick_point(const scene::Scene& scene, const passes::View& view, glm::vec2 pixel);

using passes::pixel_ray;  // passes/frame/view.h
using passes::Ray;

}  // namespace avsm::renderer
