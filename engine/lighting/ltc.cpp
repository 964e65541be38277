#include "lighting/ltc.h"

#include "lighting/hammersley.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <mutex>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <utility>

#include "passes/camera/surfaces/pbr_brdf.h"

namespace avsm::lighting {

// The shader's evaluation (shaders/common/area_light_ltc.glsl) compiled as C++, as
// pbr_brdf.h does for the BRDF: the CPU integrals below run the same code as the GPU.
namespace glsl {
using glm::mat3;
using glm::vec2;
using glm::vec3;
using glm::vec4;

using glm::abs;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::sin;
using glm::cross;
using glm::dot;
using glm::length;
using glm::max;
using glm::mix;
using glm::normalize;
using glm::sqrt;
using glm::transpose;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
#include "shaders/common/area_light_ltc.glsl"
}  // namespace
#pragma GCC diagnostic pop
}  // namespace glsl

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Sampling ------------------------------------------------------------------------------

// The fit's samples are Hammersley points (lighting/hammersley.h): low discrepancy and fixed,
// so that every evaluation of a fit's error sees the same samples and the error is a smooth
// function of the parameters, which Nelder-Mead needs.

// The clamped cosine max(z, 0) / pi, and a direction drawn from it (Malley's method).
double clamped_cosine(const glm::dvec3& unit_direction) { return std::max(unit_direction.z, 0.0) / kPi; }
glm::dvec3 sample_clamped_cosine(const glm::dvec2& u) {
  const double radius = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
  return {radius * std::cos(phi), radius * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x))};
}

// SplitMix64: the Monte Carlo reference's jitter, reproducible from its seed.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  double uniform() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30u)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27u)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31u)) >> 11u) * 0x1.0p-53;
  }

 private:
  uint64_t state_;
};

// The mean of f over the unit square from a jittered grid of about `samples` points.
template <class F>
double stratified_mean(uint32_t samples, uint32_t seed, F&& f) {
  const uint32_t side = std::max(1u, uint32_t(std::sqrt(double(samples))));
  Random random(seed);
  double sum = 0.0;
  for (uint32_t i = 0; i < side; ++i)
    for (uint32_t j = 0; j < side; ++j)
      sum += f(glm::dvec2((i + random.uniform()) / side, (j + random.uniform()) / side));
  return sum / (double(side) * side);
}

// Two unit vectors that make a right-handed frame with n (t1 x t2 = n).
void tangents(const glm::vec3& n, glm::vec3& t1, glm::vec3& t2) {
  t1 = glsl::ltc_any_tangent(n);
  t2 = glm::cross(n, t1);
}

// ---- The lobe being fitted -----------------------------------------------------------------

// The engine's GGX specular term with Fresnel 1: pbr_brdf of white metal (F0 = 1, so no
// diffuse), which the Monte Carlo reference evaluates.
pbr::PbrSurface white_metal(float roughness) { return {glm::vec3(1.0f), 1.0f, roughness}; }

// BRDF x cos for the Monte Carlo reference (n, v and l unit vectors).
double brdf_cos(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v, const glm::vec3& l) {
  const float n_dot_l = glm::dot(n, l);
  if (n_dot_l <= 0.0f) return 0.0;
  if (lobe == BrdfLobe::lambert) return n_dot_l / kPi;
  return double(pbr::pbr_brdf(white_metal(roughness), n, v, l).x) * n_dot_l;
}

// The lobe D V cos at one (roughness, view) in the shading frame (n = z, v in the xz plane),
// and GGX importance sampling: directions reflected about normals drawn from D (n.h).
//
// D and V are pbr_brdf.glsl's formulas (pbr_ggx_distribution, pbr_smith_visibility, with
// alpha from pbr_alpha) evaluated in double: at the lowest roughness, alpha^2 = 8e-7,
// float's n.h (steps of 6e-8 near 1) cannot resolve the lobe, and the fit should not learn
// that noise. The tests hold the fitted magnitudes to the engine's float BRDF.
class GgxLobe {
 public:
  GgxLobe(float roughness, double cos_theta_v)
      : alpha_(pbr::pbr_alpha(roughness)), view_(std::sqrt(1.0 - cos_theta_v * cos_theta_v), 0.0, cos_theta_v) {}

  double alpha() const { return alpha_; }

  // D V cos (Fresnel 1), 0 below the horizon.
  double value(const glm::dvec3& l) const {
    if (l.z <= 0.0) return 0.0;
    const glm::dvec3 h = glm::normalize(l + view_);
    return ggx_distribution(h.z) * smith_visibility(l.z, view_.z) * l.z;
  }
  // D V cos (1 - v.h)^5: the part of the lobe that Schlick's Fresnel scales by 1 - F0.
  double fresnel_value(const glm::dvec3& l) const {
    if (l.z <= 0.0) return 0.0;
    const glm::dvec3 h = glm::normalize(l + view_);
    const double x = std::clamp(1.0 - glm::dot(view_, h), 0.0, 1.0);
    return value(l) * (x * x) * (x * x) * x;
  }

  glm::dvec3 sample(const glm::dvec2& u) const {
    const double a2 = alpha_ * alpha_;
    const double cos2 = (1.0 - u.x) / (1.0 + (a2 - 1.0) * u.x);
    const double cos_theta = std::sqrt(cos2), sin_theta = std::sqrt(std::max(0.0, 1.0 - cos2));
    const double phi = 2.0 * kPi * u.y;
    const glm::dvec3 h(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
    return 2.0 * glm::dot(view_, h) * h - view_;
  }
  // The density of sample()'s directions. A normal that faces away from the viewer
  // reflects to a direction whose half vector is below the surface: such samples are
  // dropped (the density here leaves them out, and the estimators count them as 0).
  double sample_pdf(const glm::dvec3& l) const {
    const glm::dvec3 sum = l + view_;
    const double length = glm::length(sum);
    if (length <= 0.0) return 0.0;
    const glm::dvec3 h = sum / length;
    const double v_dot_h = glm::dot(view_, h);
    if (h.z <= 0.0 || v_dot_h <= 0.0) return 0.0;
    return ggx_distribution(h.z) * h.z / (4.0 * v_dot_h);
  }

 private:
  double ggx_distribution(double n_dot_h) const {
    const double a2 = alpha_ * alpha_, d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
  }
  // pbr_brdf clamps n.v to 1e-4.
  double smith_visibility(double n_dot_l, double n_dot_v) const {
    n_dot_v = std::clamp(n_dot_v, 1e-4, 1.0);
    const double a2 = alpha_ * alpha_;
    const double towards_view = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    const double towards_light = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    return 0.5 / std::max(towards_view + towards_light, 1e-7);
  }

  double alpha_;
  glm::dvec3 view_;
};

// ---- Linearly transformed cosines ----------------------------------------------------------

class Ltc {
 public:
  explicit Ltc(const glm::dmat3& m)
      : m_(m), inverse_(glm::inverse(m)), det_inverse_(std::abs(glm::determinant(inverse_))) {}

  const glm::dmat3& inverse() const { return inverse_; }

  // D(l) for a unit direction l.
  double density(const glm::dvec3& l) const {
    const glm::dvec3 original = inverse_ * l;
    const double length = glm::length(original);
    return clamped_cosine(original / length) * det_inverse_ / (length * length * length);
  }
  // A direction drawn from D, from a direction drawn from the cosine, and D there.
  glm::dvec3 transform(const glm::dvec3& cosine_direction, double& density) const {
    const glm::dvec3 l = m_ * cosine_direction;
    const double length = glm::length(l);
    density = clamped_cosine(cosine_direction) * det_inverse_ * length * length * length;
    return l / length;
  }

 private:
  glm::dmat3 m_, inverse_;
  double det_inverse_;
};

// The rotation by `angle` about y, from z towards x.
glm::dmat3 rotation_about_y(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return glm::dmat3(glm::dvec3(c, 0.0, -s), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(s, 0.0, c));
}

glm::dmat3 inverse_matrix_of(const glm::vec4& m) { return glm::dmat3(glsl::ltc_inverse_matrix(m)); }

// ---- Nelder-Mead ---------------------------------------------------------------------------

using Params = std::array<double, 4>;

Params along(const Params& from, const Params& to, double t) {
  Params p;
  for (size_t i = 0; i < p.size(); ++i) p[i] = from[i] + (to[i] - from[i]) * t;
  return p;
}

// Nelder and Mead's downhill simplex from `start` (a first simplex of edge `step`), until
// the simplex is smaller than `tolerance` in every parameter or `max_evaluations` ran out.
Params minimise(const std::function<double(const Params&)>& f, const Params& start, double step, double tolerance,
                int max_evaluations) {
  constexpr size_t kVertices = std::tuple_size_v<Params> + 1;
  std::array<Params, kVertices> x;
  std::array<double, kVertices> fx;
  for (size_t i = 0; i < kVertices; ++i) {
    x[i] = start;
    if (i > 0) x[i][i - 1] += step;
    fx[i] = f(x[i]);
  }
  int evaluations = int(kVertices);
  while (evaluations < max_evaluations) {
    std::array<size_t, kVertices> order;
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return fx[a] < fx[b]; });
    const size_t best = order[0], second_worst = order[kVertices - 2], worst = order[kVertices - 1];
    double size = 0.0;
    for (const Params& vertex : x)
      for (size_t k = 0; k < vertex.size(); ++k) size = std::max(size, std::abs(vertex[k] - x[best][k]));
    if (size < tolerance) break;

    Params centroid{};
    for (size_t i = 0; i + 1 < kVertices; ++i)
      for (size_t k = 0; k < centroid.size(); ++k) centroid[k] += x[order[i]][k] / double(kVertices - 1);
    const auto try_point = [&](double t) {
      const Params p = along(centroid, x[worst], t);
      ++evaluations;
      return std::pair{p, f(p)};
    };
    const auto [reflected, f_reflected] = try_point(-1.0);
    if (f_reflected < fx[best]) {
      const auto [expanded, f_expanded] = try_point(-2.0);
      std::tie(x[worst], fx[worst]) =
          f_expanded < f_reflected ? std::pair{expanded, f_expanded} : std::pair{reflected, f_reflected};
    } else if (f_reflected < fx[second_worst]) {
      std::tie(x[worst], fx[worst]) = std::pair{reflected, f_reflected};
    } else {
      const bool outside = f_reflected < fx[worst];
      const auto [contracted, f_contracted] = try_point(outside ? -0.5 : 0.5);
      if (f_contracted < std::min(f_reflected, fx[worst])) {
        std::tie(x[worst], fx[worst]) = std::pair{contracted, f_contracted};
      } else {  // shrink towards the best vertex
        for (size_t i = 0; i < kVertices; ++i) {
          if (i == best) continue;
          x[i] = along(x[best], x[i], 0.5);
          fx[i] = f(x[i]);
          ++evaluations;
        }
      }
    }
  }
  return x[size_t(std::min_element(fx.begin(), fx.end()) - fx.begin())];
}

// ---- The fit of one entry ------------------------------------------------------------------

// Samples of the normalised lobe (the fit's target) for its error estimate.
struct LobeSample {
  glm::dvec3 direction;
  double target = 0.0;      // the normalised lobe there
  double sample_pdf = 0.0;  // GGX sampling's density there
};

constexpr uint32_t kMomentSamples = 1u << 16;  // norm, fresnel and average direction
constexpr uint32_t kFitSamples = 1024;         // per technique, for the fit's error
// The paper's L3 distance: it weighs the lobe's peak, where most of the light comes from.
// (L1, L2 and a symmetric chi-square were tried too: none did better on the tests' lights
// overall; each traded some configurations for others.)
constexpr int kFitExponent = 3;

class LtcFitProblem {
 public:
  LtcFitProblem(float roughness, double cos_theta_v) : lobe_(roughness, cos_theta_v) {
    integrate_moments();
    for (uint32_t i = 0; i < kFitSamples; ++i) {
      const glm::dvec3 l = lobe_.sample(hammersley(i, kFitSamples));
      const double pdf = lobe_.sample_pdf(l);
      if (pdf > 0.0) lobe_samples_.push_back({l, lobe_.value(l) / norm_, pdf});
      cosine_samples_.push_back(sample_clamped_cosine(hammersley(i, kFitSamples)));
    }
  }

  // Parameters (ln a, ln c, b / a, angle) of M = frame R(angle) S, with frame the rotation
  // that takes z to the lobe's average direction, R(angle) a further rotation about y and
  // S = [[a, 0, b], [0, c, 0], [0, 0, 1]]: the 4 degrees of freedom of an LTC symmetric about
  // the plane of incidence. Logarithms so that a step is relative at every roughness and a
  // and c stay positive; the frame so that 0 is a good angle to start from.
  Ltc ltc(const Params& p) const {
    const double a = std::exp(p[0]), c = std::exp(p[1]), b = p[2] * a;
    glm::dmat3 s(1.0);
    s[0][0] = a;
    s[1][1] = c;
    s[2][0] = b;  // column 2, row 0
    return Ltc(frame_ * rotation_about_y(p[3]) * s);
  }
  // The parameters of M (a neighbour's solution, any scale): R(angle)^T frame^T M has the
  // form of S, up to scale, for the angle that zeroes its row 2, column 0.
  Params params(const glm::dmat3& m) const {
    const glm::dmat3 in_frame = glm::transpose(frame_) * m;
    const double angle = std::atan2(-in_frame[0][2], in_frame[0][0]);
    for (double turn : {0.0, kPi}) {  // the angle is known up to a half turn
      glm::dmat3 s = glm::transpose(rotation_about_y(angle + turn)) * in_frame;
      s /= s[2][2];
      const double a = s[0][0], c = s[1][1], b = s[2][0];
      if (a > 0.0 && c > 0.0 && std::isfinite(b)) return {std::log(a), std::log(c), b / a, angle + turn};
    }
    return isotropic_guess();
  }

  // A round lobe about the average direction, as wide as GGX's seen head on (which M =
  // diag(2 alpha, 2 alpha, 1) matches closely).
  Params isotropic_guess() const {
    const double width = std::log(2.0 * lobe_.alpha());
    return {width, width, 0.0, 0.0};
  }

  // The integral of |D - target|^exponent over the sphere, by multiple importance
  // sampling: GGX sampling and D's own, balance heuristic.
  template <int kExponent>
  double distance(const Ltc& ltc) const {
    double sum = 0.0;
    for (const LobeSample& s : lobe_samples_) {
      const double d = ltc.density(s.direction);
      sum += power<kExponent>(std::abs(d - s.target)) / (s.sample_pdf + d);
    }
    for (const glm::dvec3& cosine_direction : cosine_samples_) {
      double d = 0.0;
      const glm::dvec3 l = ltc.transform(cosine_direction, d);
      if (d <= 0.0) continue;
      const double target = lobe_.value(l) / norm_;
      sum += power<kExponent>(std::abs(d - target)) / (lobe_.sample_pdf(l) + d);
    }
    return sum / kFitSamples;
  }

  LtcEntry entry(const Ltc& ltc) const {
    glm::dmat3 inverse = ltc.inverse();
    inverse /= inverse[1][1];
    LtcEntry entry;
    entry.inverse_matrix = glm::vec4(inverse[0][0], inverse[2][0], inverse[0][2], inverse[2][2]);
    entry.magnitude = glm::vec2(norm_, fresnel_);
    return entry;
  }

 private:
  template <int kExponent>
  static double power(double x) {
    return kExponent == 1 ? x : kExponent == 2 ? x * x : x * x * x;
  }

  // norm, fresnel, and the frame whose z is the lobe's average direction.
  void integrate_moments() {
    double norm = 0.0, fresnel = 0.0;
    glm::dvec3 average(0.0);
    for (uint32_t i = 0; i < kMomentSamples; ++i) {
      const glm::dvec3 l = lobe_.sample(hammersley(i, kMomentSamples));
      const double pdf = lobe_.sample_pdf(l);
      if (pdf <= 0.0) continue;
      const double weight = lobe_.value(l) / pdf;
      norm += weight;
      fresnel += lobe_.fresnel_value(l) / pdf;
      average += weight * l;
    }
    norm_ = norm / kMomentSamples;
    fresnel_ = fresnel / kMomentSamples;
    average.y = 0.0;  // the lobe is symmetric about the xz plane
    const glm::dvec3 z = glm::length(average) > 0.0 ? glm::normalize(average) : glm::dvec3(0, 0, 1);
    frame_ = glm::dmat3(glm::dvec3(z.z, 0.0, -z.x), glm::dvec3(0.0, 1.0, 0.0), z);
  }

  GgxLobe lobe_;
  double norm_ = 0.0, fresnel_ = 0.0;
  glm::dmat3 frame_{1.0};
  std::vector<LobeSample> lobe_samples_;
  std::vector<glm::dvec3> cosine_samples_;
};

// The cosine of the view angle an entry is fitted at: pbr_brdf clamps n.v to 1e-4, so the
// geometry does too.
double fit_cos_theta(uint32_t size, uint32_t column) {
  return std::max(double(ltc_column_cos_theta(size, column)), 1e-4);
}

LtcEntry fit_entry(float roughness, double cos_theta_v, const glm::vec4& start_inverse_matrix, float* fit_error) {
  const LtcFitProblem problem(roughness, cos_theta_v);
  const auto fit_distance = [&](const Params& p) { return problem.distance<kFitExponent>(problem.ltc(p)); };
  Params best = problem.params(glm::inverse(inverse_matrix_of(start_inverse_matrix)));
  // A neighbour far off (a coarse table) can leave Nelder-Mead in a flat region: start
  // instead from the lobe's own shape if that is closer.
  const Params guess = problem.isotropic_guess();
  if (fit_distance(guess) < fit_distance(best)) best = guess;
  best = minimise(fit_distance, best, 0.1, 1e-5, 400);
  // Once more from where the first run stopped: a simplex can collapse before the minimum.
  best = minimise(fit_distance, best, 0.02, 1e-6, 200);
  const Ltc ltc = problem.ltc(best);
  if (fit_error) *fit_error = float(0.5 * problem.distance<1>(ltc));
  return problem.entry(ltc);
}

// Where fit_ggx_table starts entry (row, column): its neighbour's solution (ltc.h).
glm::vec4 fit_start(const LtcTable& table, uint32_t row, uint32_t column) {
  if (column > 0) return table.inverse_matrix[table.index(row, column - 1)];
  if (row + 1 < table.size) return table.inverse_matrix[table.index(row + 1, 0)];
  return LtcEntry{}.inverse_matrix;  // the cosine itself
}

void fit_into(LtcTable& table, uint32_t row, uint32_t column, std::vector<float>& fit_errors) {
  const size_t i = table.index(row, column);
  const LtcEntry entry = fit_entry(ltc_row_roughness(table.size, row), fit_cos_theta(table.size, column),
                                   fit_start(table, row, column), &fit_errors[i]);
  table.inverse_matrix[i] = entry.inverse_matrix;
  table.magnitude[i] = entry.magnitude;
}

// ---- Table source --------------------------------------------------------------------------

// A float literal that reads back to the same float.
std::string float_literal(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(value));
  std::string literal = text;
  if (literal.find_first_of(".e") == std::string::npos) literal += ".0";
  return literal + "f";
}

// The compiled-in table, if there is one (avsm-ltc-fit writes it; without it only
// builtin_ggx_table fails, so the tool can be built to make the first one).
#if __has_include("ltc_ggx_table.inc")
#include "ltc_ggx_table.inc"
#define AVSM_HAVE_BUILTIN_LTC_TABLE 1
#endif

}  // namespace

// ---- The table -----------------------------------------------------------------------------

void check_table_size(uint32_t size) {
  if (size < kLtcMinTableSize || size > kLtcMaxTableSize)
    throw std::invalid_argument("LTC table size " + std::to_string(size) + " is out of range: it must be from " +
                                std::to_string(kLtcMinTableSize) + " to " + std::to_string(kLtcMaxTableSize));
}

void check_table(const LtcTable& table) {
  check_table_size(table.size);
  const size_t entries = size_t(table.size) * table.size;
  if (table.inverse_matrix.size() != entries || table.magnitude.size() != entries)
    throw std::invalid_argument("LTC table of size " + std::to_string(table.size) + " holds " +
                                std::to_string(table.inverse_matrix.size()) + " matrices and " +
                                std::to_string(table.magnitude.size()) + " magnitudes, not " + std::to_string(entries));
}

float ltc_row_roughness(uint32_t size, uint32_t row) {
  return kLtcMinRoughness + (1.0f - kLtcMinRoughness) * float(row) / float(size - 1);
}

float ltc_column_cos_theta(uint32_t size, uint32_t column) {
  const float coordinate = float(column) / float(size - 1);  // sqrt(1 - cos theta)
  return 1.0f - coordinate * coordinate;
}

LtcEntry ltc_table_entry(const LtcTable& table, uint32_t row, uint32_t column) {
  const size_t i = table.index(row, column);
  return {table.inverse_matrix[i], table.magnitude[i]};
}

LtcEntry ltc_lookup(const LtcTable& table, float roughness, float cos_theta_v) {
  check_table(table);
  const float last = float(table.size - 1);
  const float x = glsl::ltc_view_coordinate(cos_theta_v) * last;
  const float y = glsl::ltc_roughness_coordinate(roughness) * last;
  const uint32_t column = std::min(uint32_t(x), table.size - 2), row = std::min(uint32_t(y), table.size - 2);
  const float fx = x - float(column), fy = y - float(row);
  LtcEntry blend{glm::vec4(0.0f), glm::vec2(0.0f)};
  const auto add = [&](uint32_t r, uint32_t c, float weight) {
    const LtcEntry e = ltc_table_entry(table, r, c);
    blend.inverse_matrix += weight * e.inverse_matrix;
    blend.magnitude += weight * e.magnitude;
  };
  add(row, column, (1.0f - fx) * (1.0f - fy));
  add(row, column + 1, fx * (1.0f - fy));
  add(row + 1, column, (1.0f - fx) * fy);
  add(row + 1, column + 1, fx * fy);
  return blend;
}

// ---- The fit -------------------------------------------------------------------------------

LtcTable fit_ggx_table(uint32_t size, uint32_t threads, LtcFitReport* report) {
  check_table_size(size);
  const auto started = std::chrono::steady_clock::now();
  LtcTable table;
  table.size = size;
  table.inverse_matrix.assign(size_t(size) * size, glm::vec4(0.0f));
  table.magnitude.assign(size_t(size) * size, glm::vec2(0.0f));
  std::vector<float> fit_errors(size_t(size) * size, 0.0f);

  // Head-on first, from the roughest row down (each row's chain starts there).
  for (uint32_t row = size; row-- > 0;) fit_into(table, row, 0, fit_errors);

  // Then the rows, each along its view angles; a row's entries are its own, so the
  // threads share nothing but the next row's number.
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, size);
  std::atomic<uint32_t> next_row{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto fit_rows = [&] {
    try {
      for (uint32_t row; (row = next_row++) < size;)
        for (uint32_t column = 1; column < size; ++column) fit_into(table, row, column, fit_errors);
    } catch (...) {
      const std::lock_guard lock(failure_mutex);
      failure = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  for (uint32_t t = 0; t < threads; ++t) workers.emplace_back(fit_rows);
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);

  if (report) {
    report->fit_error = std::move(fit_errors);
    report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  return table;
}

LtcEntry refit_ggx_entry(const LtcTable& table, uint32_t row, uint32_t column, float* fit_error) {
  check_table(table);
  if (row >= table.size || column >= table.size)
    throw std::invalid_argument("no entry (" + std::to_string(row) + ", " + std::to_string(column) +
                                ") in an LTC table of size " + std::to_string(table.size));
  return fit_entry(ltc_row_roughness(table.size, row), fit_cos_theta(table.size, column), fit_start(table, row, column),
                   fit_error);
}

// ---- Evaluation ----------------------------------------------------------------------------

float ltc_specular_magnitude(const LtcEntry& entry, float f0) {
  return glsl::ltc_specular_magnitude(entry.magnitude.x, entry.magnitude.y, glm::vec3(f0)).x;
}

LtcLobe ltc_lambert_lobe(const glm::vec3& n, const glm::vec3& v) {
  return {glsl::ltc_shading_frame(glm::normalize(n), glm::normalize(v)), 1.0f};
}

LtcLobe ltc_ggx_lobe(const LtcTable& table, float roughness, const glm::vec3& n, const glm::vec3& v) {
  const glm::vec3 unit_n = glm::normalize(n), unit_v = glm::normalize(v);
  const LtcEntry entry = ltc_lookup(table, roughness, glm::dot(unit_n, unit_v));
  return {glsl::ltc_inverse_matrix(entry.inverse_matrix) * glsl::ltc_shading_frame(unit_n, unit_v), entry.magnitude.x};
}

float clamped_cosine_polygon_integral(std::span<const glm::vec3> polygon) {
  float sum = 0.0f;
  glm::vec3 exit_point(0.0f), entry_point(0.0f);
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::vec3& a = polygon[i];
    const glm::vec3& b = polygon[(i + 1) % polygon.size()];
    sum += glsl::ltc_clipped_edge_integral(a, b);
    exit_point += glsl::ltc_exit_point(a, b);
    entry_point += glsl::ltc_entry_point(a, b);
  }
  sum += glsl::ltc_horizon_edge_integral(exit_point, entry_point);
  return sum / (2.0f * glsl::kLtcPi);
}

namespace {
float facing(float signed_integral, bool two_sided) {
  return two_sided ? std::abs(signed_integral) : std::max(signed_integral, 0.0f);
}
}  // namespace

float ltc_polygon_integral(const LtcLobe& lobe, std::span<const glm::vec3> polygon, bool two_sided) {
  std::vector<glm::vec3> mapped(polygon.size());
  std::transform(polygon.begin(), polygon.end(), mapped.begin(),
                 [&](const glm::vec3& p) { return lobe.to_cosine * p; });
  return lobe.magnitude * facing(clamped_cosine_polygon_integral(mapped), two_sided);
}

float ltc_rect_integral(const LtcLobe& lobe, const RectCorners& corners, bool two_sided) {
  return lobe.magnitude *
         glsl::ltc_rect_integral(lobe.to_cosine, corners[0], corners[1], corners[2], corners[3], two_sided);
}

float ltc_disk_integral(const LtcLobe& lobe, const glm::vec3& center, const glm::vec3& normal, float radius,
                        bool two_sided) {
  glm::vec3 t1, t2;
  tangents(glm::normalize(normal), t1, t2);
  // An inscribed regular polygon has less area than its circle; this radius gives it the same.
  const double wedge = 2.0 * kPi / kLtcDiskEdges;
  const float polygon_radius = radius * float(std::sqrt(wedge / std::sin(wedge)));
  std::array<glm::vec3, kLtcDiskEdges> polygon;
  for (int i = 0; i < kLtcDiskEdges; ++i) {
    const float angle = float(wedge * i);
    polygon[size_t(i)] = center + polygon_radius * (std::cos(angle) * t1 + std::sin(angle) * t2);
  }
  return ltc_polygon_integral(lobe, polygon, two_sided);
}

float ltc_sphere_integral(const LtcLobe& lobe, const glm::vec3& center, float radius) {
  const float distance = glm::length(center);
  if (distance <= radius) return lobe.magnitude;
  // The silhouette: the circle where the cone from the shading point touches the sphere.
  const float ratio = radius / distance;
  const glm::vec3 towards_point = -center / distance;
  const glm::vec3 silhouette_center = center + towards_point * (radius * ratio);
  return ltc_disk_integral(lobe, silhouette_center, towards_point, radius * std::sqrt(1.0f - ratio * ratio), false);
}

float ltc_rect_integral(const LtcTable& table, float roughness, const glm::vec3& n, const glm::vec3& v,
                        const RectCorners& corners, bool two_sided) {
  return ltc_rect_integral(ltc_ggx_lobe(table, roughness, n, v), corners, two_sided);
}

float ltc_lambert_rect(const glm::vec3& n, const RectCorners& corners, bool two_sided) {
  return ltc_rect_integral(ltc_lambert_lobe(n, n), corners, two_sided);
}

// ---- Monte Carlo reference -----------------------------------------------------------------

namespace {
// BRDF x cos towards a point p on an emitter (relative to the shading point) over its
// solid angle per unit area: cos_light / distance^2, with the emitter's normal.
double area_sample(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v, const glm::vec3& p,
                   const glm::vec3& emitter_normal, bool two_sided) {
  const float distance2 = glm::dot(p, p);
  const glm::vec3 l = p / std::sqrt(distance2);
  const float cos_light = facing(glm::dot(emitter_normal, -l), two_sided);
  if (cos_light <= 0.0f) return 0.0;
  return brdf_cos(lobe, roughness, n, v, l) * cos_light / distance2;
}
}  // namespace

float mc_rect_integral(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v,
                       const RectCorners& corners, uint32_t samples, uint32_t seed, bool two_sided) {
  const glm::vec3 unit_n = glm::normalize(n), unit_v = glm::normalize(v);
  const glm::vec3 edge1 = corners[1] - corners[0], edge3 = corners[3] - corners[0];
  const glm::vec3 area_normal = glm::cross(edge1, edge3);  // its length is the area
  const float area = glm::length(area_normal);
  const glm::vec3 emitter_normal = area_normal / area;
  return float(area * stratified_mean(samples, seed, [&](const glm::dvec2& u) {
                 const glm::vec3 p = corners[0] + float(u.x) * edge1 + float(u.y) * edge3;
                 return area_sample(lobe, roughness, unit_n, unit_v, p, emitter_normal, two_sided);
               }));
}

float mc_disk_integral(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v, const glm::vec3& center,
                       const glm::vec3& normal, float radius, uint32_t samples, uint32_t seed, bool two_sided) {
  const glm::vec3 unit_n = glm::normalize(n), unit_v = glm::normalize(v), emitter_normal = glm::normalize(normal);
  glm::vec3 t1, t2;
  tangents(emitter_normal, t1, t2);
  const double area = kPi * double(radius) * radius;
  return float(area * stratified_mean(samples, seed, [&](const glm::dvec2& u) {
                 const float r = radius * float(std::sqrt(u.x)), phi = float(2.0 * kPi * u.y);
                 const glm::vec3 p = center + r * (std::cos(phi) * t1 + std::sin(phi) * t2);
                 return area_sample(lobe, roughness, unit_n, unit_v, p, emitter_normal, two_sided);
               }));
}

float mc_sphere_integral(BrdfLobe lobe, float roughness, const glm::vec3& n, const glm::vec3& v,
                         const glm::vec3& center, float radius, uint32_t samples, uint32_t seed) {
  const glm::vec3 unit_n = glm::normalize(n), unit_v = glm::normalize(v);
  const double distance = glm::length(center);
  const glm::vec3 axis = distance > 0.0 ? center / float(distance) : glm::vec3(0.0f, 0.0f, 1.0f);
  glm::vec3 t1, t2;
  tangents(axis, t1, t2);
  // Uniform over the cone the sphere subtends (the whole sphere of directions from inside).
  // 1 - cos of the cone's half-angle, written so that it keeps its digits for small spheres.
  const double sin2 = std::min(1.0, (double(radius) * radius) / (distance * distance));
  const double one_minus_cos = distance > radius ? sin2 / (1.0 + std::sqrt(1.0 - sin2)) : 2.0;
  const double solid_angle = 2.0 * kPi * one_minus_cos;
  return float(solid_angle * stratified_mean(samples, seed, [&](const glm::dvec2& u) {
                 const double cos_theta = 1.0 - u.x * one_minus_cos;
                 const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
                 const double phi = 2.0 * kPi * u.y;
                 const glm::vec3 l = glm::normalize(float(sin_theta * std::cos(phi)) * t1 +
                                                    float(sin_theta * std::sin(phi)) * t2 + float(cos_theta) * axis);
                 return brdf_cos(lobe, roughness, unit_n, unit_v, l);
               }));
}

// ---- The committed table -------------------------------------------------------------------

void write_table_source(const LtcTable& table, const std::filesystem::path& path, const std::string& arguments) {
  check_table(table);
  std::ostringstream out;
  out << "// Generated by avsm-ltc-fit (tools/avsm_ltc_fit): do not edit; run it again instead.\n"
      << "// Arguments: " << arguments << "\n"
      << "// The engine's GGX specular lobe as linearly transformed cosines, included by\n"
      << "// engine/lighting/ltc.cpp; engine/lighting/ltc.h says what the rows, columns and entries are.\n"
      << "// Per entry: M^-1's (m00, m02, m20, m22) with m11 = 1, then (norm, fresnel).\n"
      << "constexpr uint32_t kBuiltinGgxTableSize = " << table.size << ";\n"
      << "constexpr float kBuiltinGgxTable[" << table.size << " * " << table.size << "][6] = {\n";
  for (uint32_t row = 0; row < table.size; ++row) {
    char heading[64];
    std::snprintf(heading, sizeof heading, "    // row %u: roughness %.4f\n", row,
                  double(ltc_row_roughness(table.size, row)));
    out << heading;
    for (uint32_t column = 0; column < table.size; ++column) {
      const LtcEntry e = ltc_table_entry(table, row, column);
      const float values[6] = {e.inverse_matrix.x, e.inverse_matrix.y, e.inverse_matrix.z,
                               e.inverse_matrix.w, e.magnitude.x,      e.magnitude.y};
      out << "    {";
      for (int k = 0; k < 6; ++k) {
        if (!std::isfinite(values[k]))
          throw std::invalid_argument("LTC table entry (" + std::to_string(row) + ", " + std::to_string(column) +
                                      ") is not finite");
        out << (k ? ", " : "") << float_literal(values[k]);
      }
      out << "},\n";
    }
  }
  out << "};\n";
  std::ofstream file(path, std::ios::binary);
  file << out.str();
  file.close();
  if (!file) throw std::runtime_error("cannot write the LTC table to '" + path.string() + "'");
}

const LtcTable& builtin_ggx_table() {
#ifdef AVSM_HAVE_BUILTIN_LTC_TABLE
  static const LtcTable table = [] {
    LtcTable t;
    t.size = kBuiltinGgxTableSize;
    for (const auto& e : kBuiltinGgxTable) {
      t.inverse_matrix.emplace_back(e[0], e[1], e[2], e[3]);
      t.magnitude.emplace_back(e[4], e[5]);
    }
    return t;
  }();
  return table;
#else
  throw std::runtime_error(
      "this build has no LTC table: run avsm-ltc-fit --out engine/lighting/ltc_ggx_table.inc and build again");
#endif
}

}  // namespace avsm::lighting
