# avsm_add_gtest_suites(TARGET [PREFIX P] [FILTER F] [PROPERTIES ...]): one CTest test per
# GoogleTest suite of TARGET (named P<Suite>, running --gtest_filter=<Suite>.*), where
# gtest_discover_tests would make one per test case.
#
# Why: a GPU test process pays its device, pipelines and scene once, about 6 s on lavapipe
# (AvsmShadowTest: 7 s a case alone, 0.3 s for the next case in the same process). One
# process per suite pays it once per suite. Cases still run in a fixed order, each under
# the fixture's validation checks, and a failing case is named in the output.
#
# FILTER: a --gtest_filter that selects the cases to register (for example "-A.b:C.d" to
# leave cases out, which another call registers with other properties). PROPERTIES go to
# every test made. Suites are found after each build (like gtest_discover_tests), from
# `TARGET --gtest_list_tests`.
set(AVSM_GTEST_SUITES_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/gtest_suites_discover.cmake)

function(avsm_add_gtest_suites target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "PREFIX;FILTER" "PROPERTIES")
  string(MD5 key "${arg_PREFIX}|${arg_FILTER}")
  string(SUBSTRING "${key}" 0 8 key)
  set(key "${target}_${key}")
  set(suites_file "${CMAKE_CURRENT_BINARY_DIR}/${key}_suites.cmake")
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${key}_include.cmake")
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_COMMAND} -DBINARY=$<TARGET_FILE:${target}> -DOUT=${suites_file}
            -DPREFIX=${arg_PREFIX} -DFILTER=${arg_FILTER} -DWORKING_DIRECTORY=${CMAKE_CURRENT_BINARY_DIR}
            -P ${AVSM_GTEST_SUITES_SCRIPT}
    BYPRODUCTS ${suites_file}
    VERBATIM)
  # Read by CTest: the suites found, then their properties.
  set(apply_properties "")
  if(arg_PROPERTIES)
    set(properties "")
    foreach(item IN LISTS arg_PROPERTIES)
      string(APPEND properties " [==[${item}]==]")
    endforeach()
    set(apply_properties "  if(avsm_suite_tests)\n    set_tests_properties(\${avsm_suite_tests} PROPERTIES${properties})\n  endif()\n")
  endif()
  file(WRITE ${include_file}
"if(EXISTS [==[${suites_file}]==])
  include([==[${suites_file}]==])
${apply_properties}else()
  add_test([==[${target}_NOT_BUILT]==] [==[${target}_NOT_BUILT]==])
endif()
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${include_file})
endfunction()
