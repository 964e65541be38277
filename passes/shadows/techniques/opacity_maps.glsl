// The comparison techniques' math, written once for GLSL and C++ like the AVSM
// core (C++ reads it through passes/shadows/techniques/opacity_maps.h). Both build from the same
// capture segments as AVSM: a segment [entry, exit] whose transmittance falls from
// 1 to exit_trans carries optical depth tau = -ln(exit_trans), spread evenly
// over its length. Depths are normalised to z in [0, 1] over the light's caster
// range [near, far].
//
// Opacity shadow maps (Kim & Neumann 2001): K planes evenly spaced in depth,
// plane k (1..K) at z = k / K holding the optical depth in front of it;
// transmittance between planes from the linearly interpolated optical depth.
//
// Fourier opacity maps (Jansen & Bavoil 2010): the extinction density sigma(z) on
// [0, 1] as a Fourier series with K terms, sigma(z) ~ a0/2 + sum_k a_k cos(2 pi k z)
// + b_k sin(2 pi k z); transmittance exp(-integral of sigma from 0 to z). Stored as
// a0, then (a_k, b_k) for k = 1..K-1: 2K - 1 numbers (padded to 2K). The series is
// reconstructed with Lanczos sigma factors against ringing.
#ifndef AVSM_OPACITY_MAPS_GLSL
#define AVSM_OPACITY_MAPS_GLSL

// An opaque segment (exit_trans 0) counts as this much optical depth: transmittance
// e^-12 = 6e-6, dark, while keeping the Fourier series' ringing bounded.
#define OPACITY_MAX_OPTICAL_DEPTH 12.0f
#define OPACITY_PI 3.14159265358979f

float opacity_segment_optical_depth(float exit_trans) {
  return min(-log(max(exit_trans, 1e-30f)), OPACITY_MAX_OPTICAL_DEPTH);
}

// Share of a segment's optical depth in front of z (all in normalised depth).
float opacity_share_in_front(float z0, float z1, float z) {
  if (z <= z0) return 0.0f;
  if (z >= z1) return 1.0f;
  return (z - z0) / (z1 - z0);
}

// ---- Opacity shadow maps ----

// Optical depth a segment adds in front of plane k of K (k = 1..K).
float osm_plane_optical_depth(float z0, float z1, float tau, int k, int planes) {
  return tau * opacity_share_in_front(z0, z1, float(k) / float(planes));
}

// Transmittance at z from the optical depths of the two planes around it
// (`before` at plane floor(z K), 0 for plane 0; `after` at the next plane).
float osm_transmittance(float before, float after, float z, int planes) {
  float u = clamp(z, 0.0f, 1.0f) * float(planes);
  return exp(-mix(before, after, u - floor(u)));
}

// ---- Fourier opacity maps ----

// Coefficients a_k (cosine, k >= 0) and b_k (sine, k >= 1) a segment adds.
float fom_cosine_coefficient(float z0, float z1, float tau, int k) {
  if (k == 0) return 2.0f * tau;
  float w = 2.0f * OPACITY_PI * float(k);
  if (z1 - z0 < 1e-6f) return 2.0f * tau * cos(w * z0);  // a step: the density is a spike
  return 2.0f * tau * (sin(w * z1) - sin(w * z0)) / (w * (z1 - z0));
}

float fom_sine_coefficient(float z0, float z1, float tau, int k) {
  float w = 2.0f * OPACITY_PI * float(k);
  if (z1 - z0 < 1e-6f) return 2.0f * tau * sin(w * z0);
  return 2.0f * tau * (cos(w * z0) - cos(w * z1)) / (w * (z1 - z0));
}

// Lanczos sigma factor of term k of K: damps the high terms so a sharp step (an
// opaque surface) rings less (Gibbs), at the price of a softer step.
float fom_window(int k, int terms) {
  if (k == 0) return 1.0f;
  float x = OPACITY_PI * float(k) / float(terms);
  return sin(x) / x;
}

// Term k's share of the optical depth in front of z: the integral of its basis
// function from 0 to z, times its (windowed) coefficients.
float fom_term_optical_depth(float a, float b, int k, int terms, float z) {
  if (k == 0) return 0.5f * a * z;
  float w = 2.0f * OPACITY_PI * float(k);
  return fom_window(k, terms) * (a * sin(w * z) + b * (1.0f - cos(w * z))) / w;
}

float fom_transmittance(float optical_depth) { return exp(-max(optical_depth, 0.0f)); }

#endif
