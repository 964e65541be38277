# Build-time GLSL -> SPIR-V. Every shader is compiled when the project builds,
# so a broken shader fails the build with glslang's file:line message.
#
#   avsm_add_shaders(<target> SOURCE_DIR <dir> SOURCES a.comp b.frag ...)
#
# writes <build>/spirv/<path relative to the repo root>.spv and makes <target>
# depend on all of them. #include dependencies are tracked through depfiles.
#
#   avsm_add_shader_variants(<target> SOURCE x.comp DEFINE NAME VALUES 4 8 ...)
#
# also compiles x.comp once per value with -DNAME=value, into <rel>.NAME-value.spv:
# what gpu::ShaderLibrary::load(path, {{"NAME", "value"}}) reads.
set(AVSM_SPIRV_DIR "${CMAKE_BINARY_DIR}/spirv" CACHE INTERNAL "Compiled SPIR-V")
set(AVSM_SHADER_INCLUDE_DIR "${CMAKE_SOURCE_DIR}/shaders" CACHE INTERNAL "GLSL include root")
# The shadow techniques' lookups ("techniques/<name>/<name>.glsl") and the dispatch over
# them that cmake/ShadowTechniques.cmake generates.
set(AVSM_TECHNIQUE_INCLUDE_DIR "${CMAKE_SOURCE_DIR}/passes/shadows" CACHE INTERNAL "GLSL include root of the techniques")
set(AVSM_GENERATED_GLSL_DIR "${AVSM_SPIRV_DIR}/glsl" CACHE INTERNAL "Generated GLSL")

# One glslangValidator command: `abs` (GLSL) to `out` (SPIR-V) with extra flags.
function(_avsm_compile_glsl abs rel out comment)
  set(include_flags -I${AVSM_SHADER_INCLUDE_DIR} -I${AVSM_TECHNIQUE_INCLUDE_DIR} -I${AVSM_GENERATED_GLSL_DIR})
  if(NANOVDB_INCLUDE_DIR)
    list(APPEND include_flags -I${NANOVDB_INCLUDE_DIR})
  endif()
  get_filename_component(out_dir "${out}" DIRECTORY)
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -E make_directory "${out_dir}"
    COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.3 -g
            ${include_flags} ${ARGN} --depfile "${out}.d" -o "${out}" "${abs}"
    DEPENDS "${abs}"
    DEPFILE "${out}.d"
    COMMENT "${comment}"
    VERBATIM)
endfunction()

function(avsm_add_shaders target)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  set(outputs)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(abs "${src}" ABSOLUTE)
    file(RELATIVE_PATH rel "${CMAKE_SOURCE_DIR}" "${abs}")
    set(out "${AVSM_SPIRV_DIR}/${rel}.spv")
    _avsm_compile_glsl("${abs}" "${rel}" "${out}" "GLSL ${rel}")
    list(APPEND outputs "${out}")
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${outputs})
endfunction()

function(avsm_add_shader_variants target)
  cmake_parse_arguments(ARG "" "SOURCE;DEFINE" "VALUES" ${ARGN})
  get_filename_component(abs "${ARG_SOURCE}" ABSOLUTE)
  file(RELATIVE_PATH rel "${CMAKE_SOURCE_DIR}" "${abs}")
  set(outputs)
  foreach(value IN LISTS ARG_VALUES)
    set(out "${AVSM_SPIRV_DIR}/${rel}.${ARG_DEFINE}-${value}.spv")
    _avsm_compile_glsl("${abs}" "${rel}" "${out}" "GLSL ${rel} ${ARG_DEFINE}=${value}" -D${ARG_DEFINE}=${value})
    list(APPEND outputs "${out}")
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${outputs})
endfunction()
