# Checks DIR/timings.json: for every measured frame, the per-pass GPU times add up to
# the frame's submit-to-completion wall time (CPU clock) within the tolerance below.
#
# Why it must hold: the executor times passes back to back on one queue and the frame
# is submitted and waited for alone, so the GPU sum can only fall short of the wall time
# by the submit/fence latency and the time before the first timestamp. On lavapipe,
# where timestamps before compute dispatches are wrong, this catches a timing scheme
# that misattributes or drops time (e.g. a dispatch's time vanishing from the sum).
# Tolerance: sum <= wall + 0.5 ms (timestamps cannot outrun the CPU clock), and
# sum >= 90% of wall minus 3 ms (submit and wake-up latency on a loaded 2-core machine).
# A decimal number of milliseconds (as nlohmann::json writes them) in whole microseconds;
# CMake's math() is integer only.
function(to_microseconds value out)
  if(NOT value MATCHES "^([0-9]+)(\\.([0-9]*))?$")
    message(FATAL_ERROR "unexpected time '${value}' in timings.json")
  endif()
  set(fraction "${CMAKE_MATCH_3}000")
  string(SUBSTRING "${fraction}" 0 3 fraction)
  math(EXPR result "${CMAKE_MATCH_1} * 1000 + 1${fraction} - 1000")
  set(${out} ${result} PARENT_SCOPE)
endfunction()

file(READ "${DIR}/timings.json" timings)
string(JSON frames LENGTH "${timings}" frames)
if(frames EQUAL 0)
  message(FATAL_ERROR "${DIR}/timings.json: no measured frames")
endif()
string(JSON passes LENGTH "${timings}" passes)
math(EXPR last_frame "${frames} - 1")
foreach(i RANGE ${last_frame})
  string(JSON gpu GET "${timings}" frames ${i} gpu_ms)
  string(JSON wall GET "${timings}" frames ${i} submit_wall_ms)
  to_microseconds("${gpu}" gpu_us)
  to_microseconds("${wall}" wall_us)
  math(EXPR upper "${wall_us} + 500")
  math(EXPR lower "${wall_us} * 9 / 10 - 3000")
  message(STATUS "frame ${i}: ${passes} passes, GPU sum ${gpu} ms, submit wall ${wall} ms")
  if(gpu_us GREATER upper)
    message(FATAL_ERROR "frame ${i}: per-pass GPU times add up to ${gpu} ms, more than the ${wall} ms the frame took")
  endif()
  if(gpu_us LESS lower)
    message(FATAL_ERROR "frame ${i}: per-pass GPU times add up to ${gpu} ms, under 90% of the ${wall} ms the frame took: time is missing")
  endif()
endforeach()
