# avsm-capture --dump-passes against a golden pass list: the shadow work a host's frame
# graph schedules for the scene must not change unnoticed. RG_UPDATE_GOLDEN=1 in the
# environment (as for the frame graph's golden plans) rewrites the golden file instead;
# review the diff before committing.
#   -DCAPTURE=<avsm-capture> -DARGS=<its other arguments, space-separated> -DOUT=<file> -DGOLDEN=<file>
separate_arguments(ARGS UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${CAPTURE} ${ARGS} --dump-passes ${OUT}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "avsm-capture --dump-passes failed (${result}):\n${output}")
endif()
if("$ENV{RG_UPDATE_GOLDEN}" STREQUAL "1")
  file(COPY_FILE ${OUT} ${GOLDEN})
  message(STATUS "updated ${GOLDEN}")
  return()
endif()
file(READ ${OUT} actual)
file(READ ${GOLDEN} expected)
if(NOT actual STREQUAL expected)
  execute_process(COMMAND diff -u ${GOLDEN} ${OUT} OUTPUT_VARIABLE difference)
  message(FATAL_ERROR "the pass list ${OUT} differs from ${GOLDEN} (RG_UPDATE_GOLDEN=1 rewrites it; "
                      "review the diff):\n${difference}")
endif()
