# cmake --install: what a host renderer needs to embed the engine.
#   <prefix>/bin/                     avsm-capture, avsm-sweep, avsm-compare (the regression gate)
#   <prefix>/lib/                     static libraries (rendergraph, gpu, scene, passes, shadows)
#   <prefix>/include/avsm/            headers: avsm/shadows.h, avsm/shadows_rendergraph.h, and gpu/, io/, scene/, passes/,
#                                     rendergraph/ as the engine includes them ("gpu/context.h",
#                                     <rendergraph/graph.h>); <avsm/gpu/context.h> works too
#   <prefix>/share/avsm/shaders/      GLSL (a host shader includes "common/shadow_lookup.glsl")
#   <prefix>/share/avsm/spirv/        the SPIR-V compiled at build time
#   <prefix>/lib/cmake/avsm/          find_package(avsm) -> avsm::avsm
# Every path in the package is relative to where it was installed, so the prefix can move.
include(CMakePackageConfigHelpers)

set(AVSM_INSTALL_INCLUDE_ROOT ${CMAKE_INSTALL_INCLUDEDIR}/avsm)
set(AVSM_INSTALL_DATA_DIR ${CMAKE_INSTALL_DATADIR}/avsm)
set(AVSM_INSTALL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/avsm)

set_target_properties(avsm_gpu PROPERTIES EXPORT_NAME gpu)
set_target_properties(avsm_scene PROPERTIES EXPORT_NAME scene)
set_target_properties(avsm_passes PROPERTIES EXPORT_NAME passes)
set_target_properties(avsm_lighting PROPERTIES EXPORT_NAME lighting)
install(TARGETS rendergraph rendergraph_vulkan avsm_gpu avsm_scene avsm_lighting avsm_passes avsm_shadows avsm
        EXPORT avsmTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})

# The command-line tools: avsm-sweep runs the avsm-capture next to it (one folder);
# avsm-compare, the regression gate, reads their output folders.
install(TARGETS avsm-capture avsm-sweep avsm-compare RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Headers, laid out as the engine includes them. The C++ builds of the shader math
# (avsm_core.h, deep_shadow.h, opacity_maps.h, hair_geometry.h, pbr_brdf.h) include GLSL from the
# source tree and serve the tests only, so they stay out.
install(DIRECTORY engine/gpu engine/io engine/scene DESTINATION ${AVSM_INSTALL_INCLUDE_ROOT}
        FILES_MATCHING PATTERN "*.h" PATTERN "fuzz" EXCLUDE)
install(DIRECTORY passes/ DESTINATION ${AVSM_INSTALL_INCLUDE_ROOT}/passes
        FILES_MATCHING PATTERN "*.h"
        PATTERN "avsm_core.h" EXCLUDE PATTERN "deep_shadow.h" EXCLUDE PATTERN "opacity_maps.h" EXCLUDE
        PATTERN "hair_geometry.h" EXCLUDE PATTERN "pbr_brdf.h" EXCLUDE)
install(DIRECTORY rendergraph/include/rendergraph rendergraph/vulkan/include/rendergraph
        DESTINATION ${AVSM_INSTALL_INCLUDE_ROOT} FILES_MATCHING PATTERN "*.h")
install(DIRECTORY engine/api/include/avsm/ DESTINATION ${AVSM_INSTALL_INCLUDE_ROOT} FILES_MATCHING PATTERN "*.h")
# The structs C++ shares with GLSL, for C++ ("shared/lights.h"); the GLSL copy is below.
install(DIRECTORY shaders/shared DESTINATION ${AVSM_INSTALL_INCLUDE_ROOT} FILES_MATCHING PATTERN "*.h")

# Shaders: GLSL (run-time compilation, and the includes of a host's shaders) and the
# prebuilt SPIR-V, both under the engine's relative names (shaders/passes/x.comp[.spv]).
set(AVSM_SHADER_PATTERNS PATTERN "*.h" PATTERN "*.glsl" PATTERN "*.vert" PATTERN "*.geom" PATTERN "*.frag" PATTERN "*.comp")
install(DIRECTORY shaders/ DESTINATION ${AVSM_INSTALL_DATA_DIR}/shaders
        FILES_MATCHING ${AVSM_SHADER_PATTERNS} PATTERN "tests" EXCLUDE)
install(DIRECTORY ${AVSM_SPIRV_DIR}/ DESTINATION ${AVSM_INSTALL_DATA_DIR}/spirv
        FILES_MATCHING PATTERN "*.spv" PATTERN "*.glsl" PATTERN "tests" EXCLUDE)
# The shadow techniques' lookups, as in the source tree (gpu::glsl_include_dirs).
install(DIRECTORY passes/shadows/techniques DESTINATION ${AVSM_INSTALL_DATA_DIR}/passes/shadows
        FILES_MATCHING PATTERN "*.glsl" PATTERN "*.comp")

# The package. The static libraries' private dependencies are link dependencies of the
# host, so the config file finds them again (the same Debian packages). OpenVDB ships a
# find module, not a config file: its (system) folder is recorded for the config file.
find_path(AVSM_OPENVDB_MODULE_DIR FindOpenVDB.cmake
          HINTS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB ${CMAKE_MODULE_PATH} NO_DEFAULT_PATH)
install(EXPORT avsmTargets NAMESPACE avsm:: DESTINATION ${AVSM_INSTALL_CMAKE_DIR})
configure_package_config_file(cmake/avsmConfig.cmake.in ${CMAKE_BINARY_DIR}/package/avsmConfig.cmake
                              INSTALL_DESTINATION ${AVSM_INSTALL_CMAKE_DIR}
                              PATH_VARS AVSM_INSTALL_DATA_DIR AVSM_INSTALL_INCLUDE_ROOT)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/avsmConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/avsmConfig.cmake ${CMAKE_BINARY_DIR}/package/avsmConfigVersion.cmake
        DESTINATION ${AVSM_INSTALL_CMAKE_DIR})
