# Configures and builds a tiny project that uses cmake/Shaders.cmake on a shader
# with an error on line 4, and checks that the build fails naming file and line.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/src/shaders")
file(WRITE "${WORK}/src/shaders/broken.comp" "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {\n  int x = not_declared;\n}\n")
file(WRITE "${WORK}/src/CMakeLists.txt"
  "cmake_minimum_required(VERSION 3.25)\nproject(broken_shader NONE)\n"
  "find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)\n"
  "include(${REPO}/cmake/Shaders.cmake)\n"
  "avsm_add_shaders(shaders SOURCES shaders/broken.comp)\n")
execute_process(COMMAND ${CMAKE_COMMAND} -S "${WORK}/src" -B "${WORK}/build" RESULT_VARIABLE configure_result
                OUTPUT_QUIET ERROR_VARIABLE configure_errors)
if(NOT configure_result EQUAL 0)
  message(FATAL_ERROR "configure failed: ${configure_errors}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/build" RESULT_VARIABLE build_result
                OUTPUT_VARIABLE build_output ERROR_VARIABLE build_errors)
if(build_result EQUAL 0)
  message(FATAL_ERROR "the broken shader built successfully")
endif()
if(NOT "${build_output}${build_errors}" MATCHES "broken.comp:4")
  message(FATAL_ERROR "the build failed without naming broken.comp:4:\n${build_output}${build_errors}")
endif()
message(STATUS "broken shader failed the build as expected")
