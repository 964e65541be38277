#include "gpu/shader_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <memory>
#include <mutex>
#include <regex>
#include <sstream>

#include "io/file_time.h"

#ifndef AVSM_DEFAULT_SOURCE_DIR
#define AVSM_DEFAULT_SOURCE_DIR "."
#endif
#ifndef AVSM_NANOVDB_INCLUDE_DIR
#define AVSM_NANOVDB_INCLUDE_DIR "/usr/include"
#endif
#ifndef AVSM_DEFAULT_SPIRV_DIR
#define AVSM_DEFAULT_SPIRV_DIR "spirv"
#endif

namespace avsm::gpu {
namespace fs = std::filesystem;

ShaderStage stage_from_path(const fs::path& path) {
  std::string ext = path.extension().string();
  if (ext == ".vert") return ShaderStage::Vertex;
  if (ext == ".geom") return ShaderStage::Geometry;
  if (ext == ".frag") return ShaderStage::Fragment;
  if (ext == ".comp") return ShaderStage::Compute;
  throw std::runtime_error(path.string() + ": unknown shader stage for extension '" + ext + "'");
}

static EShLanguage to_glslang(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex: return EShLangVertex;
    case ShaderStage::Geometry: return EShLangGeometry;
    case ShaderStage::Fragment: return EShLangFragment;
    case ShaderStage::Compute: return EShLangCompute;
  }
  return EShLangCompute;
}

static std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open shader source");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Resolves #include "x" against the including file's folder, then the include dirs.
class FileIncluder : public glslang::TShader::Includer {
 public:
  explicit FileIncluder(std::vector<fs::path> dirs) : dirs_(std::move(dirs)) {}

  IncludeResult* includeLocal(const char* name, const char* includer, size_t) override {
    fs::path base = fs::path(includer).parent_path();
    if (IncludeResult* r = try_open(base / name)) return r;
    return includeSystem(name, includer, 0);
  }
  IncludeResult* includeSystem(const char* name, const char*, size_t) override {
    for (const fs::path& dir : dirs_)
      if (IncludeResult* r = try_open(dir / name)) return r;
    return nullptr;  // glslang reports "cannot find include file" with file and line
  }
  void releaseInclude(IncludeResult* result) override {
    if (result) delete static_cast<std::string*>(result->userData);
    delete result;
  }
  const std::vector<fs::path>& opened() const { return opened_; }

 private:
  IncludeResult* try_open(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return nullptr;
    auto* text = new std::string(read_text(path));
    opened_.push_back(fs::weakly_canonical(path));
    return new IncludeResult(path.lexically_normal().string(), text->data(), text->size(), text);
  }
  std::vector<fs::path> dirs_;
  std::vector<fs::path> opened_;
};

static void init_glslang_once() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// glslang logs "ERROR: <file>:<line>: <message>"; return the first file and line.
static std::pair<std::string, int> first_error_location(const std::string& log) {
  static const std::regex pattern(R"(ERROR: (.+?):(\d+): )");
  std::smatch match;
  if (std::regex_search(log, match, pattern)) return {match[1].str(), std::stoi(match[2].str())};
  return {"", 0};
}

CompiledShader compile_glsl(const std::string& source, const std::string& source_name, ShaderStage stage,
                            const ShaderCompileOptions& options) {
  init_glslang_once();
  EShLanguage language = to_glslang(stage);
  glslang::TShader shader(language);
  const char* strings[] = {source.c_str()};
  const int lengths[] = {int(source.size())};
  const char* names[] = {source_name.c_str()};
  shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);

  std::string preamble;
  for (const auto& [name, value] : options.defines) preamble += "#define " + name + " " + value + "\n";
  shader.setPreamble(preamble.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);

  FileIncluder includer(options.include_dirs);
  auto messages = EShMessages(EShMsgSpvRules | EShMsgVulkanRules);
  if (!shader.parse(GetDefaultResources(), 460, false, messages, includer)) {
    std::string log = shader.getInfoLog();
    auto [file, line] = first_error_location(log);
    throw ShaderCompileError(source_name + ": GLSL compile failed\n" + log, file, line);
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    std::string log = program.getInfoLog();
    auto [file, line] = first_error_location(log);
    throw ShaderCompileError(source_name + ": GLSL link failed\n" + log, file, line);
  }
  CompiledShader out;
  glslang::SpvOptions spv_options;
  spv_options.generateDebugInfo = options.debug_info;
  spv_options.validate = true;
  glslang::GlslangToSpv(*program.getIntermediate(language), out.spirv, &spv_options);
  out.files = includer.opened();
  return out;
}

CompiledShader compile_glsl_file(const fs::path& path, const ShaderCompileOptions& options) {
  CompiledShader out = compile_glsl(read_text(path), path.string(), stage_from_path(path), options);
  out.files.insert(out.files.begin(), fs::weakly_canonical(path));
  return out;
}

std::vector<uint32_t> read_spirv_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error(path.string() + ": cannot open SPIR-V (was the project built?)");
  std::streamsize bytes = in.tellg();
  if (bytes <= 0 || bytes % 4 != 0) throw std::runtime_error(path.string() + ": not a SPIR-V binary");
  std::vector<uint32_t> words(size_t(bytes) / 4);
  in.seekg(0);
  in.read(reinterpret_cast<char*>(words.data()), bytes);
  if (words[0] != 0x07230203u) throw std::runtime_error(path.string() + ": bad SPIR-V magic number");
  return words;
}

std::vector<std::filesystem::path> glsl_include_dirs(const ShaderLibrary::Paths& paths) {
  std::vector<std::filesystem::path> dirs;
  for (const std::filesystem::path& dir : {paths.source_root / "shaders", paths.source_root / "passes" / "shadows",
                                           paths.spirv_root / "glsl", std::filesystem::path(AVSM_NANOVDB_INCLUDE_DIR)})
    if (std::filesystem::is_directory(dir)) dirs.push_back(dir);
  return dirs;
}

ShaderLibrary::Paths ShaderLibrary::default_paths() {
  Paths paths{AVSM_DEFAULT_SOURCE_DIR, AVSM_DEFAULT_SPIRV_DIR};
  if (const char* dir = std::getenv("AVSM_SOURCE_DIR")) paths.source_root = dir;
  if (const char* dir = std::getenv("AVSM_SPIRV_DIR")) paths.spirv_root = dir;
  return paths;
}

struct ShaderLibrary::Cache {
  struct Entry {
    CompiledShader shader;
    std::vector<std::filesystem::file_time_type> times;  // of shader.files, when compiled
    bool current() const {
      for (size_t i = 0; i < shader.files.size(); ++i)
        if (io::write_time_or_min(shader.files[i]) != times[i]) return false;
      return true;
    }
  };
  std::mutex mutex;
  std::map<std::string, Entry> entries;
};

ShaderLibrary::ShaderLibrary(Paths paths, bool compile_from_source)
    : paths_(std::move(paths)), compile_from_source_(compile_from_source), cache_(std::make_unique<Cache>()) {}

ShaderLibrary::~ShaderLibrary() = default;

std::vector<std::filesystem::path> ShaderLibrary::source_files() const {
  std::lock_guard lock(cache_->mutex);
  std::set<std::filesystem::path> files;
  for (const auto& [name, entry] : cache_->entries) files.insert(entry.shader.files.begin(), entry.shader.files.end());
  return {files.begin(), files.end()};
}

CompiledShader ShaderLibrary::compile(const std::string& relative_path, const Variant& variant) const {
  ShaderCompileOptions options;
  options.include_dirs = glsl_include_dirs(paths_);
  if (!variant.empty()) options.defines.emplace_back(variant.define, variant.value);
  return compile_glsl_file(paths_.source_root / relative_path, options);
}

std::vector<uint32_t> ShaderLibrary::load(const std::string& relative_path, const Variant& variant) const {
  const std::string name = variant.empty() ? relative_path : relative_path + "." + variant.define + "-" + variant.value;
  if (compile_from_source_) {
    std::lock_guard lock(cache_->mutex);
    auto found = cache_->entries.find(name);
    if (found != cache_->entries.end() && found->second.current()) return found->second.shader.spirv;
    Cache::Entry entry;
    // A file written while it compiled must not look current (its time stamp from after
    // the compile would vouch for the half-read content): one written since shortly
    // before, within any file system's time stamp resolution, compiles again next time
    // (max: a time no file has, where min would match a file that is gone).
    const std::filesystem::file_time_type trusted_before =
        std::filesystem::file_time_type::clock::now() - std::chrono::milliseconds(100);
    entry.shader = compile(relative_path, variant);  // throws before the cache changes
    for (const std::filesystem::path& file : entry.shader.files) {
      const std::filesystem::file_time_type time = io::write_time_or_min(file);
      entry.times.push_back(time < trusted_before ? time : std::filesystem::file_time_type::max());
    }
    return (cache_->entries[name] = std::move(entry)).shader.spirv;
  }
  return read_spirv_file(paths_.spirv_root / (name + ".spv"));
}

}  // namespace avsm::gpu
