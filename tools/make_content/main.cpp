// avsm-make-content --out DIR: writes the default scene into DIR.
#include "content.h"

#include "scene/load_error.h"

#include <cstring>
#include <exception>
#include <iostream>

namespace {

int usage(const char* problem) {
  std::cerr << "avsm-make-content: " << problem << "\nusage: avsm-make-content --out DIR\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path out;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      out = argv[++i];
    } else if (std::strcmp(argv[i], "--help") == 0) {
      usage("writes the procedural default scene (scene.json, plume.vdb, curtain.hair, stage.gltf, stage.bin), the benchmark scenes (bench_*.scene.json) and a simulated smoke sequence (plume_sequence/, plume_sequence.scene.json)");
      return 0;
    } else {
      return usage((std::string("unknown option '") + argv[i] + "'").c_str());
    }
  }
  if (out.empty()) return usage("--out is required");
  try {
    std::filesystem::create_directories(out);
    avsm::content::write_plume_vdb(out / "plume.vdb");
    avsm::content::write_curtain_hair(out / "curtain.hair");
    avsm::content::write_stage_gltf(out / "stage.gltf", out / "stage.bin");
    avsm::content::write_scene_json(out / "scene.json");
    avsm::content::write_bench_scenes(out);
    avsm::content::write_plume_sequence(out, out / "plume_sequence", 24);
  } catch (const std::exception& error) {
    std::cerr << "avsm-make-content: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
