#pragma once
// The fog's froxel grid measured against its per-pixel march (avsm-capture --compare-fog):
// the same view rendered with the fast fog, with the fog marched per pixel (every light's
// map looked up at each step) and without fog. The figure: relative L1 of the fog's
// effect, sum |fast - reference| / sum |reference - no fog| over the colour channels the
// fog changes by more than 1%. The bound the fast path is held to: 5%.
#include <cstdint>
#include <filesystem>

#include "gpu/transfer.h"

namespace avsm::capture {

struct FogComparison {
  static constexpr double kBound = 0.05;
  uint64_t fogged_pixels = 0;  // with at least one channel the fog changes by more than 1%
  double fog_effect = 0.0;     // sum |reference - no fog| over those channels
  double difference = 0.0;     // sum |fast - reference| over them
  uint64_t non_finite_pixels = 0;  // of the fast image: never within the bound
  double relative_l1() const { return fog_effect > 0.0 ? difference / fog_effect : 0.0; }
  bool within_bound() const { return non_finite_pixels == 0 && relative_l1() <= kBound; }
};

// The three images must have one size.
FogComparison compare_fog(const gpu::ImageRGBA32F& fast, const gpu::ImageRGBA32F& reference,
                          const gpu::ImageRGBA32F& without_fog);

// fog_quality.json: the figures and the bound.
void write_fog_comparison(const std::filesystem::path& file, const FogComparison& comparison);

}  // namespace avsm::capture
