// Procedural hair: a curtain of strands hanging from a rod, in cyHair format.
#include "content.h"

#include "scene/hair.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace avsm::content {
namespace {

constexpr int kColumns = 900;           // strands along the rod
constexpr int kLayers = 3;              // rows of roots across the rod
constexpr float kRodHalfLength = 0.6f;  // metres
constexpr float kRodRadius = 0.02f;

void add_strand(scene::HairGroom& groom, std::uint32_t id, float root_x, float root_y, float root_z) {
  const float length = 0.95f + 0.45f * hash01(id, 1);
  const int points = 16 + int(16.0f * hash01(id, 2));  // 16 to 31: cyHair strands may differ
  const float phase = 6.2832f * hash01(id, 3);
  const float sway = 0.03f + 0.05f * hash01(id, 4);
  const float spread = (hash01(id, 5) - 0.5f) * 0.12f;
  for (int p = 0; p < points; ++p) {
    const float t = float(p) / float(points - 1);
    const float y = root_y - t * length;
    // Gentle waves that grow towards the tip, plus a slow fan-out.
    const float x = root_x + spread * t * t + 0.015f * std::sin(phase + 9.0f * t) * t;
    const float z = root_z + sway * std::sin(phase + 4.0f * t) * t;
    groom.points.emplace_back(x, y, z);
  }
  groom.strand_offsets.push_back(std::uint32_t(groom.points.size()));
  groom.strand_width.push_back(0.0006f + 0.0003f * hash01(id, 6));  // metres: chunky, to show in shadow maps
  groom.strand_opacity.push_back(0.35f + 0.2f * hash01(id, 7));
  const float shade = hash01(id, 8);
  groom.strand_color.emplace_back(0.55f + 0.25f * shade, 0.38f + 0.2f * shade, 0.2f + 0.1f * shade);
}

}  // namespace

std::size_t write_curtain_hair(const std::filesystem::path& file) {
  scene::HairGroom groom;
  groom.width_kind = scene::StrandWidth::absolute;
  groom.strand_offsets.push_back(0);
  std::uint32_t id = 0;
  for (int layer = 0; layer < kLayers; ++layer)
    for (int column = 0; column < kColumns; ++column, ++id) {
      const float jitter = (hash01(id, 9) - 0.5f) / kColumns;
      const float root_x = -kRodHalfLength + 2.0f * kRodHalfLength * ((column + 0.5f) / kColumns + jitter);
      const float around = (float(layer) - 1.0f) * 0.6f;  // roots around the underside of the rod
      add_strand(groom, id, root_x, -kRodRadius * std::cos(around), kRodRadius * std::sin(around));
    }
  scene::validate_groom(groom, file);
  const auto bytes = scene::encode_cyhair(groom);
  std::ofstream stream(file, std::ios::binary);
  stream.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!stream) throw std::runtime_error(file.string() + ": cannot write");
  return groom.strand_count();
}

}  // namespace avsm::content
