#pragma once
// GLSL -> SPIR-V at run time through the glslang library (hot reload needs it),
// and loading of the SPIR-V that the build compiled ahead of time.
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace avsm::gpu {

enum class ShaderStage { Vertex, Geometry, Fragment, Compute };

// .vert .geom .frag .comp
ShaderStage stage_from_path(const std::filesystem::path& path);

// A compile error. what() holds glslang's full log; file() and line() point at
// the first error, which may be inside an #include'd file.
class ShaderCompileError : public std::runtime_error {
 public:
  ShaderCompileError(const std::string& message, std::string file, int line)
      : std::runtime_error(message), file_(std::move(file)), line_(line) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  std::string file_;
  int line_;
};

struct CompiledShader {
  std::vector<uint32_t> spirv;
  // The source and every file it included: what a hot reloader should watch.
  std::vector<std::filesystem::path> files;
};

struct ShaderCompileOptions {
  std::vector<std::filesystem::path> include_dirs;
  std::vector<std::pair<std::string, std::string>> defines;
  bool debug_info = true;
};

CompiledShader compile_glsl(const std::string& source, const std::string& source_name, ShaderStage stage,
                            const ShaderCompileOptions& options = {});
CompiledShader compile_glsl_file(const std::filesystem::path& path, const ShaderCompileOptions& options = {});

// Finds shaders by their path relative to the repository root, e.g.
// "shaders/fullscreen.vert". Prebuilt SPIR-V comes from the build's spirv/
// folder; with compile_from_source, the GLSL is compiled now (hot reload). Those
// compiled shaders are kept and compiled again only when their source or one of
// its includes changed on disk, so rebuilding every pipeline after one edit
// recompiles just the shaders that edit touched.
class ShaderLibrary {
 public:
  struct Paths {
    std::filesystem::path source_root;  // repository root holding shaders/
    std::filesystem::path spirv_root;   // <build>/spirv
  };
  // AVSM_SOURCE_DIR / AVSM_SPIRV_DIR from the environment, else the build's own.
  static Paths default_paths();

  explicit ShaderLibrary(Paths paths = default_paths(), bool compile_from_source = false);
  ~ShaderLibrary();

  // Throws ShaderCompileError (from source) or std::runtime_error (a missing file).
  // With `variant`, the shader compiled with `#define <variant.define> <variant.value>`:
  // prebuilt as <path>.<define>-<value>.spv (avsm_add_shader_variants, cmake/Shaders.cmake).
  struct Variant {
    std::string define;
    std::string value;
    bool empty() const { return define.empty(); }
  };
  std::vector<uint32_t> load(const std::string& relative_path, const Variant& variant = {}) const;
  // Compiles now, bypassing the cache.
  CompiledShader compile(const std::string& relative_path, const Variant& variant = {}) const;
  const Paths& paths() const { return paths_; }
  bool compiles_from_source() const { return compile_from_source_; }

  // Every source and include file of the shaders compiled from source so far
  // (what a hot reloader watches).
  std::vector<std::filesystem::path> source_files() const;

 private:
  struct Cache;
  Paths paths_;
  bool compile_from_source_;
  std::unique_ptr<Cache> cache_;
};

std::vector<uint32_t> read_spirv_file(const std::filesystem::path& path);

// Where the engine's GLSL includes resolve, for `paths`: shaders/, the shadow
// techniques' folders (passes/: "techniques/<name>/<name>.glsl"), the GLSL the build
// generates next to the SPIR-V (<spirv_root>/glsl: the technique dispatch), NanoVDB's
// headers. Folders that do not exist are left out.
std::vector<std::filesystem::path> glsl_include_dirs(const ShaderLibrary::Paths& paths);

}  // namespace avsm::gpu
