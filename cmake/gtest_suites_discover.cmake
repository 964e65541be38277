# Writes OUT: add_test() per GoogleTest suite of BINARY (cmake/GTestSuites.cmake), each
# running exactly the suite's cases that FILTER selects, and avsm_suite_tests, the list of
# their names. PREFIX starts the names.
set(list_args --gtest_list_tests)
if(FILTER)
  list(APPEND list_args "--gtest_filter=${FILTER}")
endif()
execute_process(COMMAND ${BINARY} ${list_args} RESULT_VARIABLE status OUTPUT_VARIABLE listing
                ERROR_VARIABLE errors TIMEOUT 60)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${BINARY} --gtest_list_tests failed (${status}):\n${listing}${errors}")
endif()
# Suite lines start in column 0 and end with '.' (a typed or parameterized suite may add
# "  # TypeParam = ..."); its cases follow, indented.
string(REPLACE "\n" ";" lines "${listing}")
set(suites "")
set(suite "")
foreach(line IN LISTS lines)
  if(line MATCHES "^([A-Za-z_][A-Za-z0-9_/]*)\\.")
    set(suite "${CMAKE_MATCH_1}")
    list(APPEND suites "${suite}")
    set(cases_${suite} "")
  elseif(suite AND line MATCHES "^  ([A-Za-z_][A-Za-z0-9_/]*)")
    list(APPEND cases_${suite} "${suite}.${CMAKE_MATCH_1}")
  endif()
endforeach()
set(text "set(avsm_suite_tests \"\")\n")
foreach(suite IN LISTS suites)
  string(REPLACE "/" "_" name "${PREFIX}${suite}")
  list(JOIN cases_${suite} ":" cases)
  string(APPEND text
    "add_test([==[${name}]==] [==[${BINARY}]==] [==[--gtest_filter=${cases}]==])\n"
    "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==])\n"
    "list(APPEND avsm_suite_tests [==[${name}]==])\n")
endforeach()
file(WRITE "${OUT}" "${text}")
