#pragma once
// Area lights (rectangles, disks, spheres) with linearly transformed cosines, LTCs (Heitz,
// Dupuy, Hill and Neubelt, "Real-Time Polygonal-Light Shading with Linearly Transformed
// Cosines", SIGGRAPH 2016): our own fit of the engine's GGX specular lobe
// (shaders/common/pbr_brdf.glsl), its table, and a CPU integrator with a Monte Carlo
// reference to hold it to.
//
// The method. For a view direction and roughness, the lobe BRDF x cos (as a function of the
// light direction l) is approximated by magnitude x D(l), where D is a clamped cosine
// max(z, 0) / pi transformed by a 3x3 matrix M: D(l) = D_o(M^-1 l / |M^-1 l|) |det M^-1| /
// |M^-1 l|^3. D's integral over a polygon is the cosine's integral over the polygon mapped
// by M^-1, which has a closed form (shaders/common/area_light_ltc.glsl, which this file's
// evaluation runs as C++). Lambert's lobe is a clamped cosine, so it needs no table.
//
// Conventions: the shading frame has z along the normal n and x towards the viewer (v's
// part along the surface); light positions are relative to the shading point; a one-sided
// light emits on the side its normal cross(p1 - p0, p3 - p0) points to (corners counter-
// clockwise seen from there). The GGX lobe is the engine's specular term with Fresnel 1,
// D x V (white metal: F0 = 1); roughness is glTF's perceptual roughness (alpha = r^2).
#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace avsm::lighting {

// ---- The table -----------------------------------------------------------------------------
//
// size x size entries, row-major: row r is the perceptual roughness
// kLtcMinRoughness + (1 - kLtcMinRoughness) r / (size - 1) (pbr_brdf.glsl's clamp, so the
// table covers every roughness the BRDF shades with); column c the view angle, at
// sqrt(1 - cos theta_v) = c / (size - 1). That coordinate is close to theta / sqrt(2) near
// head-on, where the lobe's skew (m02) grows linearly with theta: over 1 - cos theta, which
// goes as theta^2, the skew would be a square root that a bilinear blend follows badly
// (measured: up to 120% off a light's integral at 5-12 degrees with 32 columns, against 1%
// here). Its steps grow only 1.4x from head-on to grazing (1.3 to 1.8 degrees with 64
// columns). A texture with bilinear filtering reads the table at area_light_ltc.glsl's
// ltc_table_uv, x the column and y the row.
//
// Per entry:
//  - inverse_matrix: (m00, m02, m20, m22) of M^-1 in the shading frame, scaled so that
//    m11 = 1 (an LTC does not change with M's scale); the other entries are 0.
//  - magnitude: (norm, fresnel), norm = the integral of D V cos over the sphere (the
//    lobe's directional albedo with Fresnel 1) and fresnel = the same integral weighted by
//    (1 - v.h)^5. With Schlick's F = F0 + (1 - F0)(1 - v.h)^5 the lobe's integral is
//    F0 norm + (1 - F0) fresnel = F0 (norm - fresnel) + fresnel (ltc_specular_magnitude).
struct LtcTable {
  uint32_t size = 0;
  std::vector<glm::vec4> inverse_matrix;
  std::vector<glm::vec2> magnitude;

  size_t index(uint32_t row, uint32_t column) const { return size_t(row) * size + column; }
};

// One entry, or the bilinear blend of four.
struct LtcEntry {
  glm::vec4 inverse_matrix{1.0f, 0.0f, 0.0f, 1.0f};
  glm::vec2 magnitude{1.0f, 0.0f};
};

inline constexpr float kLtcMinRoughness = 0.03f;
inline constexpr uint32_t kLtcMinTableSize = 2;
inline constexpr uint32_t kLtcMaxTableSize = 256;
// The committed table's size (engine/lighting/ltc_ggx_table.inc). The blend of entries
// then adds at most 0.7% to a light's integral up to 78 degrees and 2.6% beyond, well under
// the fit's own error there (with 32 x 32: 8% and 18%); the file compiles in a second or two.
inline constexpr uint32_t kLtcDefaultTableSize = 64;

// Throws std::invalid_argument naming the size unless kLtcMinTableSize <= size <= kLtcMaxTableSize.
void check_table_size(uint32_t size);
// Throws std::invalid_argument unless the table's size is valid and its arrays hold size^2 entries.
void check_table(const LtcTable& table);

float ltc_row_roughness(uint32_t size, uint32_t row);
float ltc_column_cos_theta(uint32_t size, uint32_t column);
LtcEntry ltc_table_entry(const LtcTable& table, uint32_t row, uint32_t column);
// Bilinear between the four entries around (roughness, cos theta_v), as a filtered texture reads them.
LtcEntry ltc_lookup(const LtcTable& table, float roughness, float cos_theta_v);

// ---- The fit -------------------------------------------------------------------------------
//
// Per entry, M = R S with R a rotation about y (starting where it takes z to the lobe's
// average direction) and S = [[a, 0, b], [0, c, 0], [0, 0, 1]]: the 4 degrees of freedom of
// an LTC symmetric about the plane of incidence. Nelder-Mead finds those that minimise the
// L3 distance (the paper's) between D and the normalised lobe BRDF cos / norm, estimated
// with the same low-discrepancy samples each time (half from GGX's distribution of normals,
// half from D, weighted by the balance heuristic). Each entry starts from its neighbour's
// solution: column 0 (head on) from the row above it, rougher, and the roughest from the
// cosine itself (GGX with alpha = 1 is close to it); the other columns from the column
// before. Rows then run in parallel; the result does not depend on the thread count.
//
// Accuracy. A single LTC cannot follow GGX everywhere: the clamped cosine has no long tail,
// and towards grazing the lobe is cut by the horizon. The lights' integrals come out within
// 2% for views up to about 30 degrees (3.5% for small lights on the roughest surfaces);
// tests/lighting/ltc_test.cpp measures the rest: at 60 degrees up to 6% for large lights
// and 16% for small ones, at 75 degrees 17% and 53% (a small light off the lobe's peak).
// The table's blend adds little to that (kLtcDefaultTableSize).

struct LtcFitReport {
  // Per entry, half the L1 distance between D and the normalised lobe: the share of the
  // lobe's energy that D puts elsewhere, 0..1.
  std::vector<float> fit_error;
  double seconds = 0.0;
};

// threads 0: one per hardware thread. Throws std::invalid_argument on a bad size.
LtcTable fit_ggx_table(uint32_t size, uint32_t threads = 0, LtcFitReport* report = nullptr);
// The entry (row, column) fitted again from the same start fit_ggx_table used, read from
// `table` (its neighbour): a table the fit wrote comes back unchanged.
LtcEntry refit_ggx_entry(const LtcTable& table, uint32_t row, uint32_t column, float* fit_error = nullptr);

// ---- Evaluation ----------------------------------------------------------------------------

// A lobe at one shading point: world directions map into the clamped cosine's space by
// to_cosine; the lobe's integral over a region is magnitude x the cosine's over its image.
struct LtcLobe {
  glm::mat3 to_cosine{1.0f};
  float magnitude = 1.0f;
};

// A table entry's magnitude with Schlick's Fresnel: F0 norm + (1 - F0) fresnel.
float ltc_specular_magnitude(const LtcEntry& entry, float f0);

LtcLobe ltc_lambert_lobe(const glm::vec3& n, const glm::vec3& v);  // magnitude 1: Lambert's 1/pi x cos
LtcLobe ltc_ggx_lobe(const LtcTable& table, float roughness, const glm::vec3& n, const glm::vec3& v);

// The clamped cosine's integral over a convex planar polygon (vertices in the cosine's
// space, any distance from the origin) clipped to the upper hemisphere; signed, positive
// when the vertices run counter-clockwise seen from the origin.
float clamped_cosine_polygon_integral(std::span<const glm::vec3> polygon);

// The integral of the lobe (BRDF x cos) over a light, each given relative to the shading
// point. A one-sided light that faces away gives 0; a two-sided one shines both ways.
// A light (or part of one) below the surface's horizon: Lambert's is exact, its cosine is
// the surface's; GGX's, as the paper's, is clipped to the cosine's horizon only, so D's
// small share below the surface counts where the light is.
using RectCorners = std::array<glm::vec3, 4>;  // a rectangle's corners in order round it
float ltc_polygon_integral(const LtcLobe& lobe, std::span<const glm::vec3> polygon, bool two_sided);
float ltc_rect_integral(const LtcLobe& lobe, const RectCorners& corners, bool two_sided);
// A disk as a regular polygon of kLtcDiskEdges of the same area; a sphere as the disk of
// its silhouette (where the cone from the point touches it), which subtends the same solid
// angle. A point inside the sphere gets the whole lobe.
inline constexpr int kLtcDiskEdges = 64;
float ltc_disk_integral(const LtcLobe& lobe, const glm::vec3& center, const glm::vec3& normal, float radius,
                        bool two_sided);
float ltc_sphere_integral(const LtcLobe& lobe, const glm::vec3& center, float radius);

// The integral of the engine's GGX specular term with Fresnel 1 (D V) x cos over a rectangle.
float ltc_rect_integral(const LtcTable& table, float roughness, const glm::vec3& n, const glm::vec3& v,
                        const RectCorners& corners, bool two_sided);
// The rectangle's form factor: Lambert's 1/pi x cos integrated over it (exact).
float ltc_lambert_rect(const glm::vec3& n, const RectCorners& corners, bool two_sided);

// ---- Monte Carlo reference -----------------------------------------------------------------
//
// The same integrals by sampling the light itself (stratified: a jittered grid of about
// `samples` points, from `seed`): uniformly over a rectangle's or disk's area with the
// solid-angle Jacobian cos_light / distance^2, uniformly over the cone a sphere subtends.
// The BRDFs are the engine's own (pbr_brdf.glsl). A rectangle is the parallelogram that
// corners 1 and 3 span from corner 0.

enum class BrdfLobe {
  lambert,       // 1/pi
  ggx_specular,  // pbr_brdf of white metal: D V, Fresnel 1
};

float mc_rect_integral(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v,
                       const RectCorners& corners, uint32_t samples, uint32_t seed, bool two_sided = false);
float mc_disk_integral(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v, const glm::vec3& center,
                       const glm::vec3& normal, float radius, uint32_t samples, uint32_t seed, bool two_sided = false);
float mc_sphere_integral(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v,
                         const glm::vec3& center, float radius, uint32_t samples, uint32_t seed);

// ---- The committed table -------------------------------------------------------------------

// Writes `table` as C++ source (engine/lighting/ltc_ggx_table.inc), headed by a comment
// that names avsm-ltc-fit and `arguments`, the command line that made it. Throws
// std::invalid_argument for a malformed table or a value that is not finite, and
// std::runtime_error naming the file when it cannot be written.
void write_table_source(const LtcTable& table, const std::filesystem::path& path, const std::string& arguments);
// The table compiled in from ltc_ggx_table.inc.
const LtcTable& builtin_ggx_table();

}  // namespace avsm::lighting
