#pragma once
// avsm-make-content: writes the project's default scene (procedural, needs no
// outside data). Every generator is deterministic: no clocks, no std::random
// distributions (their output differs between standard libraries); noise and
// jitter come from integer hashes.
#include <cstdint>
#include <filesystem>

namespace avsm::content {

// Smoke plume: OpenVDB float fog grid "density" within 96 x 128 x 96 voxels
// of 2.5 cm, base centred at the origin, rising along +Y.
void write_plume_vdb(const std::filesystem::path& file);

// A curtain of hair hanging from a 1.2 m rod along X at the origin, down -Y.
// cyHair format with absolute thickness (metres). Returns the strand count.
std::size_t write_curtain_hair(const std::filesystem::path& file);

// glTF (.gltf + .bin): floor, box, sphere, and a stand (two posts and the rod)
// whose rod sits where write_curtain_hair's strands hang from once both are
// placed as in the scene file.
void write_stage_gltf(const std::filesystem::path& gltf_file, const std::filesystem::path& bin_file);

// The scene file referencing the three assets above.
void write_scene_json(const std::filesystem::path& file);

// The benchmark scenes (bench_*.scene.json) into `dir`, next to the default scene's assets.
void write_bench_scenes(const std::filesystem::path& dir);

// A short smoke sequence, simulated: a buoyant plume advected (semi-Lagrangian) through a
// swirling wind, frames 1..frame_count as dir/plume.####.vdb with the grids a fluid cache
// has (float "density" and "temperature", vec3 "velocity"), 3 cm voxels; and
// plume_sequence.scene.json in `scene_dir`, the default stage with it playing at 24 fps.
void write_plume_sequence(const std::filesystem::path& scene_dir, const std::filesystem::path& dir, int frame_count);

// Overwrites the random UUID OpenVDB stamps every file with, so that the build writes
// byte-identical content every time.
void make_uuid_deterministic(const std::filesystem::path& file);

// Integer hash to [0, 1): deterministic "random" numbers.
float hash01(std::uint32_t a, std::uint32_t b = 0, std::uint32_t c = 0);

}  // namespace avsm::content
