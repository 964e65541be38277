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
//   bench_sparse.scene.json         two plumes and the hair curtain about 20 m apart over
//                                   a large ground, one sun: mostly empty light space, what
//                                   clustered maps (seed 004) are for (bench/avsm/lights.py)
//   bench_many_lights.scene.json    the default scene's content under 16 shadowed lights,
//                                   directional, spot and point, so that the first N of them
//                                   measure the cost per light (bench/avsm/lights.py)
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

// The stage scaled 12x across (not up) is the ground: its floor becomes 96 m square, the box
// a platform, the sphere a low mound and the stand a gate of two pillars and a beam. One
// plume stands on the platform, one on the mound, and the curtain hangs from the beam: three
// groups of casters 20-25 m apart, so a single map fitted around them is mostly empty.
const char* const kSparse = R"({
  "version": 1,
  "description": "Benchmark: two smoke plumes and the hair curtain 20-25 m apart over a 96 m ground (the stage scaled 12x across), one sun. Sparse light space: clustered shadow maps against one fitted map.",
  "models": [ { "name": "ground", "file": "stage.gltf", "transform": { "scale": [12.0, 1.0, 12.0] } } ],
  "volumes": [
    { "name": "plume_platform", "file": "plume.vdb", "grid": "density",
      "transform": { "translation": [22.8, 0.6, 13.2], "scale": 1.5 }, "extinction_scale": 1.5, "albedo": [0.9, 0.9, 0.9] },
    { "name": "plume_mound", "file": "plume.vdb", "grid": "density",
      "transform": { "translation": [-2.4, 0.6, 16.8], "scale": 1.5 }, "extinction_scale": 1.5, "albedo": [0.9, 0.9, 0.9] }
  ],
  "hair": [ { "name": "curtain", "file": "curtain.hair", "transform": { "translation": [12.0, 1.9, -3.6] } } ],
  "lights": [
    { "name": "sun", "type": "directional", "direction": [0.35, -1.0, 0.25],
      "color": [1.0, 0.96, 0.9], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 512, "filter": "bilinear", "sort": true } }
  ],
  "cameras": [
    { "name": "main", "position": [10.0, 16.0, 42.0], "target": [10.0, 0.5, 7.0], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 50.0, "near": 0.1, "far": 150.0 }
  ]
}
)";

// The default scene's content under 16 shadowed lights in the order directional, spot,
// point, spot (repeated), so that every first 4k of them hold the same mix: 4 suns from
// different sides, 8 spots on a ring around the stage, 4 point lights (6 faces each)
// above it; every map 256^2, so N lights cost N times one on average.
const char* const kManyLights = R"({
  "version": 1,
  "description": "Benchmark: the default scene's smoke plume, hair curtain and stage under 16 shadowed lights (4 directional, 8 spot, 4 point, interleaved), every map 256^2. The first N lights measure the cost per light.",
  "models": [ { "name": "stage", "file": "stage.gltf" } ],
  "volumes": [
    { "name": "plume", "file": "plume.vdb", "grid": "density", "transform": { "translation": [-1.3, 0.0, -0.4] },
      "extinction_scale": 1.5, "albedo": [0.9, 0.9, 0.9] }
  ],
  "hair": [ { "name": "curtain", "file": "curtain.hair", "transform": { "translation": [1.0, 1.9, -0.3] } } ],
  "lights": [
    { "name": "sun_1", "type": "directional", "direction": [0.35, -1.0, 0.25], "color": [1.0, 0.96, 0.9], "intensity": 0.2,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_1", "type": "spot", "position": [4.01, 3.6, 0.94], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.85, 0.9, 1.0], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "point_1", "type": "point", "position": [1.81, 2.6, 1.57], "range": 7.0, "color": [1.0, 0.85, 0.75], "intensity": 1.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_2", "type": "spot", "position": [1.96, 3.2, 3.41], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.9, 1.0, 0.9], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "sun_2", "type": "directional", "direction": [-0.5, -1.0, 0.3], "color": [1.0, 0.96, 0.9], "intensity": 0.2,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_3", "type": "spot", "position": [-1.24, 3.6, 3.71], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.85, 0.9, 1.0], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "point_2", "type": "point", "position": [-1.87, 2.6, 1.51], "range": 7.0, "color": [1.0, 0.85, 0.75], "intensity": 1.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_4", "type": "spot", "position": [-3.71, 3.2, 1.66], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.9, 1.0, 0.9], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "sun_3", "type": "directional", "direction": [0.25, -1.0, -0.6], "color": [1.0, 0.96, 0.9], "intensity": 0.2,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_5", "type": "spot", "position": [-4.01, 3.6, -1.54], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.85, 0.9, 1.0], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "point_3", "type": "point", "position": [-1.81, 2.6, -2.17], "range": 7.0, "color": [1.0, 0.85, 0.75], "intensity": 1.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_6", "type": "spot", "position": [-1.96, 3.2, -4.01], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.9, 1.0, 0.9], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "sun_4", "type": "directional", "direction": [-0.3, -1.0, -0.45], "color": [1.0, 0.96, 0.9], "intensity": 0.2,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_7", "type": "spot", "position": [1.24, 3.6, -4.31], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.85, 0.9, 1.0], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "point_4", "type": "point", "position": [1.87, 2.6, -2.11], "range": 7.0, "color": [1.0, 0.85, 0.75], "intensity": 1.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } },
    { "name": "spot_8", "type": "spot", "position": [3.71, 3.2, -2.26], "target": [0.0, 0.9, -0.3],
      "inner_cone_deg": 22.0, "outer_cone_deg": 30.0, "color": [0.9, 1.0, 0.9], "intensity": 2.0,
      "shadow": { "technique": "avsm", "nodes": 8, "resolution": 256, "filter": "bilinear", "sort": true } }
  ],
  "cameras": [
    { "name": "main", "position": [0.2, 1.7, 5.8], "target": [0.1, 1.1, 0.0], "up": [0.0, 1.0, 0.0],
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
  write_text(dir / "bench_sparse.scene.json", kSparse);
  write_text(dir / "bench_many_lights.scene.json", kManyLights);
}

}  // namespace avsm::content
