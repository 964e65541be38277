# What the host examples' projects (examples/host_embed, host_raw) share: include() this
# after project(), then avsm_host_example(<name>) builds <name> from main.cpp against the
# installed package (avsm::avsm), with its shaders/ compiled at run time (HOST_SHADER_DIR:
# the engine's compiler and the package's GLSL include directory, Shadows::compile_glsl)
# and this folder's scene, checks, host device and push constants on the include path.
set(CMAKE_CXX_STANDARD 20)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()

find_package(avsm 0.1 REQUIRED)

set(AVSM_HOST_COMMON_DIR ${CMAKE_CURRENT_LIST_DIR})  # here, not the caller's folder

function(avsm_host_example name)
  add_executable(${name} main.cpp)
  target_link_libraries(${name} PRIVATE avsm::avsm)
  target_compile_definitions(${name} PRIVATE HOST_SHADER_DIR="${CMAKE_CURRENT_SOURCE_DIR}/shaders")
  target_include_directories(${name} PRIVATE ${AVSM_HOST_COMMON_DIR})
endfunction()
