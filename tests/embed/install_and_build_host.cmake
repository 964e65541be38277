# cmake -DBUILD_DIR=<engine build> -DSOURCE_DIR=<repo> -DWORK=<scratch> [-DBUILD_TYPE=Release]
#       -P install_and_build_host.cmake
# Installs the engine into WORK/staging, moves the install to WORK/prefix (the package
# must not depend on where it was installed, nor on the source and build trees), then
# configures and builds each host example (examples/host_embed, examples/host_raw)
# against it in a fresh WORK/<example>-build.
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result}):\n${output}")
  endif()
  message(STATUS "${what}: ok")
endfunction()

file(REMOVE_RECURSE "${WORK}")
run_step("install into the staging prefix" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK}/staging")
file(RENAME "${WORK}/staging" "${WORK}/prefix")

# The package's CMake files may name system paths only.
file(GLOB package_files "${WORK}/prefix/lib/cmake/avsm/*.cmake")
if(NOT package_files)
  message(FATAL_ERROR "no CMake package under ${WORK}/prefix/lib/cmake/avsm")
endif()
foreach(file IN LISTS package_files)
  file(READ "${file}" text)
  foreach(tree IN ITEMS "${SOURCE_DIR}" "${BUILD_DIR}" "${WORK}/staging")
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${file} names ${tree}: the installed package must not depend on it")
    endif()
  endforeach()
endforeach()
foreach(expected IN ITEMS include/avsm/shadows.h include/avsm/shadows_rendergraph.h include/avsm/passes/shadows/shadow_pass_list.h
                          include/avsm/gpu/context.h include/avsm/rendergraph/graph.h
                          share/avsm/shaders/common/shadow_lookup.glsl share/avsm/spirv/passes/shadows/techniques/avsm/avsm_resolve.comp.AVSM_NODES-8.spv)
  if(NOT EXISTS "${WORK}/prefix/${expected}")
    message(FATAL_ERROR "the install lacks ${expected}")
  endif()
endforeach()

# host_raw embeds the engine through plain Vulkan values only: none of the engine's frame
# graph, bindings or push descriptors in its sources (nor in the common ones it includes).
file(GLOB raw_sources "${SOURCE_DIR}/examples/host_raw/*.cpp" "${SOURCE_DIR}/examples/host_raw/shaders/*"
                      "${SOURCE_DIR}/examples/common/*")
foreach(file IN LISTS raw_sources)
  file(READ "${file}" text)
  foreach(forbidden IN ITEMS "rg::" "rendergraph/" "gpu::Bindings" "gpu::Pipeline" "vkCmdPushDescriptorSet"
                             "PUSH_DESCRIPTOR")
    string(FIND "${text}" "${forbidden}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${file} uses ${forbidden}: host_raw must see plain Vulkan values only")
    endif()
  endforeach()
endforeach()

foreach(example IN ITEMS host_embed host_raw)
  set(build "${WORK}/${example}-build")
  run_step("configure examples/${example} against the package"
    ${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/${example}" -B "${build}"
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} "-DCMAKE_PREFIX_PATH=${WORK}/prefix")
  run_step("build examples/${example}" ${CMAKE_COMMAND} --build "${build}" -j 2)
endforeach()
