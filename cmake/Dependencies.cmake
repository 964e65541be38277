# Every dependency comes from a Debian package (see tools/install-deps.sh).
find_package(Vulkan REQUIRED)
find_package(glslang CONFIG REQUIRED)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(tinyexr CONFIG REQUIRED)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
pkg_check_modules(SPIRV_CROSS REQUIRED IMPORTED_TARGET spirv-cross-c-shared)
# The viewer only (engine/viewer): a window and Dear ImGui (libimgui.a holds the GLFW backend).
if(AVSM_BUILD_VIEWER)
  find_package(glfw3 CONFIG REQUIRED)
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
endif()

find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
# PNanoVDB.h compiles as GLSL: shaders include it as "nanovdb/PNanoVDB.h".
find_path(NANOVDB_INCLUDE_DIR nanovdb/PNanoVDB.h REQUIRED)

if(AVSM_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
