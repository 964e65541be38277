#include "gpu/shader_compiler.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gpu/spirv_reflect.h"

namespace avsm {
namespace shader_compiler_test {  // one per file: test targets are unity builds
namespace {

namespace fs = std::filesystem;

fs::path write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

fs::path scratch_dir() {
  fs::path dir = fs::temp_directory_path() / "avsm_shader_compiler_test";
  fs::create_directories(dir);
  return dir;
}

TEST(ShaderCompiler, CompilesAndReflectsAValidShader) {
  gpu::ShaderLibrary library(gpu::ShaderLibrary::default_paths(), /*compile_from_source=*/true);
  gpu::CompiledShader shader = library.compile("shaders/tests/fill.comp");
  ASSERT_FALSE(shader.spirv.empty());
  EXPECT_EQ(shader.spirv[0], 0x07230203u);
  // The shader and every file it includes are reported, for hot reload.
  std::vector<std::string> names;
  for (const auto& file : shader.files) names.push_back(file.filename().string());
  EXPECT_EQ(names, (std::vector<std::string>{"fill.comp", "test_common.glsl", "fill.h", "gpu_struct.h"}));
  gpu::ShaderReflection reflection = gpu::reflect_spirv(shader.spirv);
  EXPECT_EQ(reflection.stage, VK_SHADER_STAGE_COMPUTE_BIT);
  ASSERT_TRUE(reflection.push_constants.has_value());
  EXPECT_EQ(reflection.push_constants->name, "FillPush");
  ASSERT_EQ(reflection.bindings.size(), 1u);
  EXPECT_EQ(reflection.bindings[0].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

TEST(ShaderCompiler, RuntimeCompileMatchesTheBuildTimeResult) {
  gpu::ShaderLibrary prebuilt;
  gpu::ShaderLibrary from_source(gpu::ShaderLibrary::default_paths(), true);
  gpu::ShaderReflection a = gpu::reflect_spirv(prebuilt.load("shaders/tests/fill.comp"));
  gpu::ShaderReflection b = gpu::reflect_spirv(from_source.load("shaders/tests/fill.comp"));
  EXPECT_EQ(a.bindings.size(), b.bindings.size());
  EXPECT_EQ(a.local_size, b.local_size);
}

TEST(ShaderCompiler, ErrorNamesFileAndLine) {
  fs::path file = write_file(scratch_dir() / "broken.comp",
                             "#version 460\n"
                             "layout(local_size_x = 1) in;\n"
                             "void main() {\n"
                             "  float x = 1.0;\n"
                             "  x = undefined_thing * 2.0;\n"
                             "}\n");
  try {
    gpu::compile_glsl_file(file);
    FAIL() << "expected a compile error";
  } catch (const gpu::ShaderCompileError& e) {
    EXPECT_EQ(e.line(), 5) << e.what();
    EXPECT_NE(e.file().find("broken.comp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("undefined_thing"), std::string::npos) << e.what();
  }
}

TEST(ShaderCompiler, ErrorInsideAnIncludeNamesTheIncludedFile) {
  fs::path dir = scratch_dir() / "include_error";
  write_file(dir / "lib" / "helpers.glsl", "float helper() {\n  return 1.0 +;\n}\n");
  fs::path file = write_file(dir / "main.comp",
                             "#version 460\n"
                             "#extension GL_GOOGLE_include_directive : require\n"
                             "#include \"lib/helpers.glsl\"\n"
                             "layout(local_size_x = 1) in;\n"
                             "void main() { helper(); }\n");
  try {
    gpu::compile_glsl_file(file);
    FAIL() << "expected a compile error";
  } catch (const gpu::ShaderCompileError& e) {
    EXPECT_NE(e.file().find("helpers.glsl"), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), 2) << e.what();
  }
}

TEST(ShaderCompiler, MissingIncludeIsReported) {
  fs::path file = write_file(scratch_dir() / "missing_include.comp",
                             "#version 460\n"
                             "#extension GL_GOOGLE_include_directive : require\n"
                             "#include \"does_not_exist.glsl\"\n"
                             "layout(local_size_x = 1) in;\n"
                             "void main() {}\n");
  try {
    gpu::compile_glsl_file(file);
    FAIL() << "expected a compile error";
  } catch (const gpu::ShaderCompileError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.glsl"), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), 3) << e.what();
  }
}

TEST(ShaderCompiler, MissingSourceFileIsAClearError) {
  try {
    gpu::compile_glsl_file(scratch_dir() / "nope.comp");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nope.comp"), std::string::npos);
  }
}

TEST(SpirvReflect, RejectsGarbage) {
  std::vector<uint32_t> garbage = {1, 2, 3, 4, 5, 6};
  EXPECT_THROW(gpu::reflect_spirv(garbage), std::runtime_error);
  std::vector<uint32_t> truncated = {0x07230203u, 0x10000, 0, 10, 0, (50u << 16) | 5u};
  EXPECT_THROW(gpu::reflect_spirv(truncated), std::runtime_error);
}

}  // namespace
}  // namespace shader_compiler_test
}  // namespace avsm
