#include "scene/hair.h"

#include "scene/load_error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace avsm::scene {
namespace {

std::string format_vec3(const glm::vec3& v) {
  std::ostringstream text;
  text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return text.str();
}

bool is_finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void validate_offsets(const HairGroom& groom, const std::filesystem::path& file) {
  if (groom.strand_offsets.size() < 2) throw LoadError(file, "hair has no strands");
  if (groom.strand_offsets.front() != 0) throw LoadError(file, "first strand does not start at point 0");
  for (std::size_t s = 0; s + 1 < groom.strand_offsets.size(); ++s)
    if (groom.strand_offsets[s + 1] <= groom.strand_offsets[s])
      throw LoadError(file, "strand " + std::to_string(s) + " has no points");
  if (groom.strand_offsets.back() != groom.points.size())
    throw LoadError(file, "strands cover " + std::to_string(groom.strand_offsets.back()) +
                              " points but there are " + std::to_string(groom.points.size()));
  const std::size_t strands = groom.strand_count();
  if (groom.strand_width.size() != strands || groom.strand_opacity.size() != strands ||
      groom.strand_color.size() != strands)
    throw LoadError(file, "per-strand width/opacity/colour arrays do not match the strand count " +
                              std::to_string(strands));
}

void validate_points(const HairGroom& groom, const std::filesystem::path& file) {
  for (std::size_t i = 0; i < groom.points.size(); ++i) {
    if (is_finite(groom.points[i])) continue;
    const auto strand = std::upper_bound(groom.strand_offsets.begin(), groom.strand_offsets.end(), i) -
                        groom.strand_offsets.begin() - 1;
    throw LoadError(file, "point " + std::to_string(i) + " (strand " + std::to_string(strand) +
                              ") is not finite: " + format_vec3(groom.points[i]));
  }
}

void validate_strand_attributes(const HairGroom& groom, const std::filesystem::path& file) {
  for (std::size_t s = 0; s < groom.strand_count(); ++s) {
    const std::string strand = "strand " + std::to_string(s);
    const float width = groom.strand_width[s];
    if (!std::isfinite(width) || width < 0.0f)
      throw LoadError(file, strand + ": width " + std::to_string(width) + " is not a finite number >= 0");
    const float opacity = groom.strand_opacity[s];
    if (!(opacity >= 0.0f && opacity <= 1.0f))
      throw LoadError(file, strand + ": opacity " + std::to_string(opacity) + " is outside [0, 1]");
    const glm::vec3 color = groom.strand_color[s];
    if (!is_finite(color) || glm::any(glm::lessThan(color, glm::vec3(0.0f))))
      throw LoadError(file, strand + ": colour " + format_vec3(color) + " is not finite and >= 0");
  }
}

}  // namespace

void validate_groom(HairGroom& groom, const std::filesystem::path& file) {
  validate_offsets(groom, file);
  validate_points(groom, file);
  validate_strand_attributes(groom, file);
  groom.bounds = Bounds{};
  for (const glm::vec3& p : groom.points) groom.bounds.extend(p);
}

void transform_groom(HairGroom& groom, const glm::mat4& transform) {
  for (glm::vec3& p : groom.points) p = glm::vec3(transform * glm::vec4(p, 1.0f));
  if (groom.width_kind == StrandWidth::absolute) {
    // Widths are lengths: a uniform scale of the placement scales them too.
    const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(transform))));
    for (float& width : groom.strand_width) width *= scale;
  }
  groom.bounds = Bounds{};
  for (const glm::vec3& p : groom.points) groom.bounds.extend(p);
}

}  // namespace avsm::scene
