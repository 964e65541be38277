// avsm_fuzz_make_seeds OUT_DIR CONTENT_DIR: small valid inputs for every fuzz
// target, one folder per target, so that fuzzing starts from real structure.
#include "scene/binary_reader.h"
#include "scene/hair.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using avsm::scene::HairGroom;

void write(const fs::path& file, const void* data, std::size_t size) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary).write(static_cast<const char*>(data), std::streamsize(size));
}
void write(const fs::path& file, const std::vector<std::byte>& bytes) { write(file, bytes.data(), bytes.size()); }
void write(const fs::path& file, const std::string& text) { write(file, text.data(), text.size()); }

template <class T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

HairGroom small_groom(bool thick) {
  HairGroom groom;
  groom.strand_offsets = {0};
  for (int s = 0; s < 3; ++s) {
    for (int p = 0; p < 4; ++p) groom.points.emplace_back(float(s), float(-p), 0.5f * p);
    groom.strand_offsets.push_back(std::uint32_t(groom.points.size()));
    groom.strand_width.push_back(thick ? 0.5f + s : 1.0f);
    groom.strand_opacity.push_back(0.5f);
    groom.strand_color.emplace_back(0.2f, 0.3f, 0.4f);
  }
  return groom;
}

// A TressFX 4 file with every array: positions and thickness from encode_tfx,
// then per-strand UVs, per-vertex UVs and per-vertex colours appended and
// their offsets (header bytes 16, 20, 28) set.
std::vector<std::byte> tfx4_with_uvs_and_colours() {
  const HairGroom groom = small_groom(true);
  auto bytes = avsm::scene::encode_tfx(groom, avsm::scene::TfxVersion::v4);
  auto append_floats = [&](std::size_t header_field, std::size_t floats, float value) {
    while (bytes.size() % 8 != 0) bytes.push_back(std::byte{0});
    const auto offset = std::uint32_t(bytes.size());
    std::memcpy(bytes.data() + header_field, &offset, 4);
    for (std::size_t i = 0; i < floats; ++i) avsm::scene::detail::append_bytes(bytes, value);
  };
  append_floats(16, 2 * groom.strand_count(), 0.5f);  // float2 per strand
  append_floats(20, 2 * groom.points.size(), 0.25f);  // float2 per vertex
  append_floats(28, 4 * groom.points.size(), 0.75f);  // float4 per vertex
  return bytes;
}

std::string base64(const std::string& bytes) {
  static const char* const table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint8_t(bytes[i]) << 16) | (i + 1 < bytes.size() ? std::uint8_t(bytes[i + 1]) << 8 : 0) |
                            (i + 2 < bytes.size() ? std::uint8_t(bytes[i + 2]) : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

// A quad (two triangles, with uvs and a 1x1 PNG texture) and a line strip.
void write_gltf_seeds(const fs::path& dir) {
  std::string bin;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) append(bin, v);       // positions @0
  for (float v : {0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 1.f}) append(bin, v);                            // uvs @48
  for (std::uint16_t i : {0, 1, 2, 0, 2, 3, 0, 1, 2, 3}) append(bin, i);                               // indices @80
  // A 1x1 red RGBA PNG.
  static const unsigned char kPng[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
      0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x00, 0x05, 0x00, 0x01, 0xff,
      0x56, 0xc7, 0x2f, 0x0d, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  const std::string png(reinterpret_cast<const char*>(kPng), sizeof kPng);
  nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {1, 2, 3}}, {"children", {1}}}, {{"mesh", 0}, {"scale", {-1, 1, 1}}}}},
      {"meshes", {{{"primitives",
                    {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}},
                     {{"attributes", {{"POSITION", 0}}}, {"indices", 3}, {"mode", 3}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}, {"alphaMode", "MASK"}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", "data:image/png;base64," + base64(png)}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                     {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                     {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
                     {{"bufferView", 2}, {"byteOffset", 12}, {"componentType", 5123}, {"count", 4}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                       {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                       {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 20}}}},
      {"buffers", {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}}}};
  write(dir / "quad.gltf", gltf.dump());

  // The same as GLB: JSON chunk and BIN chunk, each padded to 4 bytes.
  gltf["buffers"][0].erase("uri");
  std::string json_text = gltf.dump();
  while (json_text.size() % 4) json_text += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string glb = "glTF";
  append(glb, std::uint32_t{2});
  append(glb, std::uint32_t(12 + 8 + json_text.size() + 8 + bin.size()));
  append(glb, std::uint32_t(json_text.size()));
  glb += "JSON" + json_text;
  append(glb, std::uint32_t(bin.size()));
  glb += std::string("BIN\0", 4) + bin;
  write(dir / "quad.glb", glb);
}

// Header, one metadata entry and one grid descriptor with a fake payload.
void write_vdb_seed(const fs::path& file) {
  std::string vdb;
  append(vdb, std::int64_t{0x56444220});
  append(vdb, std::uint32_t{224});
  append(vdb, std::uint32_t{10});
  append(vdb, std::uint32_t{0});
  vdb += '\1';
  vdb += "a75bd1f0-0000-4000-8000-000000000001";
  auto string = [&](const std::string& s) {
    append(vdb, std::uint32_t(s.size()));
    vdb += s;
  };
  append(vdb, std::int32_t{1});
  string("creator");
  string("string");
  append(vdb, std::uint32_t{4});
  vdb += "seed";
  append(vdb, std::int32_t{1});
  string("density");
  string("Tree_float_5_4_3");
  string("");
  const std::uint64_t grid_pos = vdb.size() + 24;
  append(vdb, grid_pos);
  append(vdb, grid_pos + 16);
  append(vdb, grid_pos + 64);
  vdb += std::string(64, '\0');
  write(file, vdb);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: avsm_fuzz_make_seeds OUT_DIR CONTENT_DIR\n";
    return 2;
  }
  const fs::path out = argv[1], content = argv[2];
  write(out / "tfx" / "plain.tfx", avsm::scene::encode_tfx(small_groom(false)));
  write(out / "tfx" / "thickness.tfx", avsm::scene::encode_tfx(small_groom(true)));
  write(out / "tfx" / "v4_plain.tfx", avsm::scene::encode_tfx(small_groom(false), avsm::scene::TfxVersion::v4));
  write(out / "tfx" / "v4_all_arrays.tfx", tfx4_with_uvs_and_colours());
  write(out / "cyhair" / "all_arrays.hair", avsm::scene::encode_cyhair(small_groom(true)));
  auto defaults_only = avsm::scene::encode_cyhair(small_groom(false));
  defaults_only.resize(128 + 6 + 12 * 12);
  const std::uint32_t points_only = 2 | 1;  // keep segments + points
  std::memcpy(defaults_only.data() + 12, &points_only, 4);
  write(out / "cyhair" / "segments_points.hair", defaults_only);
  write_gltf_seeds(out / "gltf");
  write_vdb_seed(out / "vdb_layout" / "one_grid.vdb");
  fs::create_directories(out / "scene_json");
  for (const auto& entry : fs::recursive_directory_iterator(content))
    if (entry.path().extension() == ".json") fs::copy_file(entry.path(), out / "scene_json" / entry.path().filename(), fs::copy_options::overwrite_existing);
  return 0;
}
