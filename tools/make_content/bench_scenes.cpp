// The benchmark scenes, in the spirit of the AVSM paper's comparisons, built from
// the default scene's assets (they are written into the same folder):
//   bench_smoke_columns.scene.json  three smoke columns in a row, lit along the row,
//                                   so each shadows the next (volumetric self- and
//                                   inter-shadowing, long segment lists)
//   bench_smoke_hair.scene.json     smoke and a hair curtain overlapping above the
//                                   stage floor (mixed casters over an opaque receiver)
//   hair_in_front_of_smoke.scene.json  the hair curtain hanging between the camera and
//                                   a lit plume, for the depth order of hair and smoke
//   lighting_cache_settings.scene.json  a plume without lighting cache beside one with
//                                   coarse cells, for the per-volume cache settings
#include "content.h"

#include <fstream>
#include <stdexcept>
#include <string>

namespace avsm::content {
namespace {

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream stream(file);
  stream << text;
  if (!stream) throw std::runtime_error(file.string() + ": cannot write");
}

const char* const kSmokeColumns = R"({
  "version": 1,
  "description": "Benchmark: three smoke columns in a row, lit along the row so each shadows the next, over the stage floor.",
  "models": [ { "name": "stage", "file": "stage.gltf" } ],
  "volumes": [
    { "name": "column_left", "file": "plume.vdb", "grid": "density", "transform": { "translation": [-1.8, 0.0, -0.6] },
      "extinction_scale": 2.0, "albedo": [0.9, 0.9, 0.9] },
    { "name": "column_middle", "file": "plume.vdb", "grid": "density", "transform": { "translation": [0.0, 0.0, -0.6] },
      "extinction_scale": 2.0, "albedo": [0.9, 0.9, 0.9] },
    { "name": "column_right", "file": "plume.vdb", "grid": "density", "transform": { "translation": [1.8, 0.0, -0.6] },
      "extinction_scale": 2.0, "albedo": [0.9, 0.9, 0.9] }
  ],
  "lights": [
    { "name": "low_sun", "type": "directional", "direction": [1.0, -0.45, 0.1],
      "color": [1.0, 0.95, 0.85], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } }
  ],
  "cameras": [
    { "name": "main", "position": [0.0, 1.8, 6.5], "target": [0.0, 1.3, -0.6], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 45.0, "near": 0.05, "far": 60.0 }
  ]
}
)";

const char* const kSmokeHair = R"({
  "version": 1,
  "description": "Benchmark: a smoke plume rising through a hair curtain, both shadowing the stage floor under a high sun.",
  "models": [ { "name": "stage", "file": "stage.gltf" } ],
  "volumes": [
    { "name": "plume", "file": "plume.vdb", "grid": "density", "transform": { "translation": [0.6, 0.0, -0.5] },
      "extinction_scale": 1.5, "albedo": [0.9, 0.9, 0.9] }
  ],
  "hair": [ { "name": "curtain", "file": "curtain.hair", "transform": { "translation": [1.0, 1.9, -0.3] } } ],
  "lights": [
    { "name": "high_sun", "type": "directional", "direction": [-0.25, -1.0, -0.35],
      "color": [1.0, 0.96, 0.9], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } }
  ],
  "cameras": [
    { "name": "main", "position": [0.8, 1.9, 5.0], "target": [0.8, 1.0, -0.4], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 45.0, "near": 0.05, "far": 60.0 }
  ]
}
)";

}  // namespace

const char* const kHairInFrontOfSmoke = R"({
  "version": 1,
  "description": "Test: the hair curtain hangs between the camera and a lit smoke plume, so strands are seen in front of smoke and smoke in front of the stage.",
  "models": [ { "name": "stage", "file": "stage.gltf" } ],
  "volumes": [
    { "name": "plume", "file": "plume.vdb", "grid": "density", "transform": { "translation": [0.6, 0.0, -1.2] },
      "extinction_scale": 2.0, "albedo": [0.9, 0.9, 0.9] }
  ],
  "hair": [ { "name": "curtain", "file": "curtain.hair", "transform": { "translation": [0.4, 1.9, 0.6] } } ],
  "lights": [
    { "name": "sun", "type": "directional", "direction": [0.35, -1.0, -0.45],
      "color": [1.0, 0.96, 0.9], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } }
  ],
  "cameras": [
    { "name": "main", "position": [0.9, 1.6, 4.8], "target": [0.9, 1.2, -1.0], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 45.0, "near": 0.05, "far": 60.0 }
  ]
}
)";

const char* const kLightingCacheSettings = R"({
  "version": 1,
  "description": "Test: two plumes side by side, the left without a lighting cache (the fast march looks the shadow maps up along the ray), the right with coarse cache cells (4 voxels).",
  "models": [ { "name": "stage", "file": "stage.gltf" } ],
  "volumes": [
    { "name": "uncached", "file": "plume.vdb", "grid": "density", "transform": { "translation": [-1.0, 0.0, -0.6] },
      "extinction_scale": 1.5, "albedo": [0.9, 0.9, 0.9], "lighting_cache": "off" },
    { "name": "coarse", "file": "plume.vdb", "grid": "density", "transform": { "translation": [1.0, 0.0, -0.6] },
      "extinction_scale": 1.5, "albedo": [0.9, 0.9, 0.9], "lighting_cache": { "downsample": 4 } }
  ],
  "lights": [
    { "name": "sun", "type": "directional", "direction": [0.35, -1.0, 0.25],
      "color": [1.0, 0.96, 0.9], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } }
  ],
  "cameras": [
    { "name": "main", "position": [0.0, 1.7, 5.8], "target": [0.0, 1.2, -0.6], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 45.0, "near": 0.05, "far": 60.0 }
  ]
}
)";

void write_bench_scenes(const std::filesystem::path& dir) {
  write_text(dir / "lighting_cache_settings.scene.json", kLightingCacheSettings);
  write_text(dir / "hair_in_front_of_smoke.scene.json", kHairInFrontOfSmoke);
  write_text(dir / "bench_smoke_columns.scene.json", kSmokeColumns);
  write_text(dir / "bench_smoke_hair.scene.json", kSmokeHair);
}

}  // namespace avsm::content
