# Copies the sweep folder SWEEP to OUT and marks its first done job failed in OUT's
# index.json, as a commit that makes a job's capture crash would: avsm-compare SWEEP OUT
# must fail on that job and name it.
file(REMOVE_RECURSE "${OUT}")
file(COPY "${SWEEP}/" DESTINATION "${OUT}")
file(READ "${OUT}/index.json" index)
string(JSON jobs LENGTH "${index}" jobs)
math(EXPR last "${jobs} - 1")
foreach(i RANGE ${last})
  string(JSON status GET "${index}" jobs ${i} status)
  if(status STREQUAL "done")
    string(JSON index SET "${index}" jobs ${i} status "\"failed\"")
    string(JSON index SET "${index}" jobs ${i} exit_code 1)
    string(JSON index SET "${index}" jobs ${i} error "\"planted: the capture crashed\"")
    file(WRITE "${OUT}/index.json" "${index}")
    return()
  endif()
endforeach()
message(FATAL_ERROR "${SWEEP}/index.json has no done job")
