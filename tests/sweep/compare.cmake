# The regression gate (avsm-compare, engine/sweep/compare.h): its checks on synthetic
# reports and sweep folders, then on real captures made once (fixture compare_captures;
# the alpha casters scene needs nothing outside the project, and 96x54 with 2 frames
# keeps each capture to seconds): an equal pair passes, a pair whose shadow maps have
# half the resolution is flagged on the image, and a copy with planted regressions is
# flagged on each; two captures of different settings fail unless allowed. Every comparison
# writes JUnit, checked with xmllint.
add_executable(avsm_compare_tests compare_test.cpp)
target_link_libraries(avsm_compare_tests PRIVATE avsm_sweep nlohmann_json::nlohmann_json GTest::gtest GTest::gtest_main)
gtest_discover_tests(avsm_compare_tests DISCOVERY_TIMEOUT 60)

set(COMPARE_OUT ${CMAKE_CURRENT_BINARY_DIR}/compare)
set(COMPARE_CAPTURE_ARGS --scene ${CMAKE_SOURCE_DIR}/content/examples/alpha_casters.scene.json
    --width 96 --height 54 --frames 2 --quiet --compare-to uncompressed)
foreach(capture "Base;64" "Same;64" "HalfShadowResolution;32")
  list(POP_FRONT capture name resolution)
  add_test(NAME compare.Capture${name}
    COMMAND ${CMAKE_COMMAND} -E env XDG_RUNTIME_DIR=/tmp
            $<TARGET_FILE:avsm-capture> ${COMPARE_CAPTURE_ARGS} --shadow-res ${resolution} --out ${COMPARE_OUT}/${name})
  set_tests_properties(compare.Capture${name} PROPERTIES FIXTURES_SETUP compare_captures)
endforeach()
# What a broken commit would do, planted in a copy of the base capture: the biggest pass
# 4x slower, light 0's map 4x larger, light 0's mean shadow error 0.5.
add_test(NAME compare.PlantRegressions
  COMMAND ${CMAKE_COMMAND} -DBASE=${COMPARE_OUT}/Base -DOUT=${COMPARE_OUT}/Planted "-DPASS=shadow quality"
          -P ${CMAKE_SOURCE_DIR}/tests/cmake/plant_regression.cmake)
set_tests_properties(compare.PlantRegressions PROPERTIES FIXTURES_REQUIRED compare_captures
                                                         FIXTURES_SETUP compare_planted)

# avsm-compare Base NEW --junit compare/<name>.xml [ARGN], expecting exit status
# `expect_exit` and output matching every pattern of `expect`.
function(add_compare_test name new expect_exit expect)
  set(junit ${COMPARE_OUT}/${name}.xml)
  add_test(NAME compare.${name}
    COMMAND ${CMAKE_COMMAND}
            "-DCOMMAND=$<TARGET_FILE:avsm-compare>;${COMPARE_OUT}/Base;${COMPARE_OUT}/${new};--junit;${junit};${ARGN}"
            -DEXPECT_EXIT=${expect_exit} "-DEXPECT=${expect}" -DJUNIT=${junit} -DSUITES=1
            -P ${CMAKE_SOURCE_DIR}/tests/cmake/check_compare.cmake)
  set_tests_properties(compare.${name} PROPERTIES FIXTURES_REQUIRED "compare_captures;compare_planted")
endfunction()
add_compare_test(EqualSettingsPass Same 0 "image psnr +inf \\(equal\\);PASS: no threshold crossed")
# The image alone: the resolution that differs is listed (--allow-different-settings), not failed.
add_compare_test(HalfShadowResolutionFails HalfShadowResolution 1
  "setting 'light sun' resolution +64 +32 +equal +- differs \\(allowed by --allow-different-settings\\);FAIL: 1 check crossed;capture: frame.exr differs from BASE: PSNR [0-9.]+ dB \\(limit 40 dB, image.min_psnr_db\\)"
  --allow-different-settings)
# lavapipe's times are judged here (timing.judge_cpu_devices): the planted copy has no noise.
add_compare_test(PlantedRegressionsFail Planted 1
  "FAIL: 4 checks crossed;pass 'shadow quality' took x[0-9.]+ its BASE time;the frame took x[0-9.]+ its BASE GPU time;light 'sun': the mean shadow error against the exact reference rose;memory 'sun' map_bytes grew x4.00"
  --thresholds ${CMAKE_SOURCE_DIR}/tests/data/judge_cpu_timings.json)

# Captures of different settings, the issue's AVSM-8 against AVSM-4 in kind: the default scene's
# AVSM-4 and AVSM-16 captures (capture.QualityAvsm4 and capture.QualityAvsm16 in
# tests/CMakeLists.txt, fixture capture_quality_nodes: 96x54, 32-texel maps, 1 frame, validation,
# alike but for --nodes). The gate fails on each light's nodes setting; with
# --allow-different-settings it lists them and judges the figures as usual, which pass
# (16 nodes: less error, map bytes under memory.min_increase_bytes).
set(NODES_CAPTURES ${CMAKE_BINARY_DIR}/tests)
foreach(case "DifferentSettingsFail;1;setting 'light sun' nodes +4 +16 +equal +FAIL;FAIL: 2 checks crossed;capture: setting 'light sun' nodes is 4 in BASE but 16 in NEW: the figures compare different settings \\(--allow-different-settings compares them anyway\\);capture: setting 'light key_spot' nodes is 4 in BASE but 16 in NEW"
             "DifferentSettingsAllowed;0;setting 'light sun' nodes +4 +16 +equal +- differs \\(allowed by --allow-different-settings\\);setting 'light key_spot' nodes +4 +16 +equal +- differs;PASS: no threshold crossed")
  list(POP_FRONT case name expect_exit)
  set(allow)
  if(expect_exit EQUAL 0)
    set(allow ";--allow-different-settings")
  endif()
  add_test(NAME compare.${name}
    COMMAND ${CMAKE_COMMAND}
            "-DCOMMAND=$<TARGET_FILE:avsm-compare>;${NODES_CAPTURES}/capture_quality_avsm4;${NODES_CAPTURES}/capture_quality_avsm16;--junit;${COMPARE_OUT}/${name}.xml${allow}"
            -DEXPECT_EXIT=${expect_exit} "-DEXPECT=${case}" -DJUNIT=${COMPARE_OUT}/${name}.xml -DSUITES=1
            -P ${CMAKE_SOURCE_DIR}/tests/cmake/check_compare.cmake)
  set_tests_properties(compare.${name} PROPERTIES FIXTURES_REQUIRED capture_quality_nodes)
endforeach()

# Two sweep folders: the local run's (sweep.LocalRun: 5 jobs done, 1 failed) against
# itself passes; against a copy in which a done job failed, that job fails.
set(LOCAL_SWEEP ${CMAKE_CURRENT_BINARY_DIR}/local_sweep)
add_test(NAME compare.PlantLostJob
  COMMAND ${CMAKE_COMMAND} -DSWEEP=${LOCAL_SWEEP} -DOUT=${COMPARE_OUT}/lost_job_sweep
          -P ${CMAKE_SOURCE_DIR}/tests/cmake/plant_lost_job.cmake)
set_tests_properties(compare.PlantLostJob PROPERTIES FIXTURES_REQUIRED sweep_local_run FIXTURES_SETUP lost_job_sweep)
foreach(case "SweepAgainstItselfPasses;${LOCAL_SWEEP};0;PASS: no threshold crossed"
             "SweepWithALostJobFails;${COMPARE_OUT}/lost_job_sweep;1;FAIL: 1 check crossed;job '[^']+' was done in BASE but is failed in NEW: planted: the capture crashed")
  list(POP_FRONT case name new expect_exit)
  add_test(NAME compare.${name}
    COMMAND ${CMAKE_COMMAND} "-DCOMMAND=$<TARGET_FILE:avsm-compare>;${LOCAL_SWEEP};${new};--junit;${COMPARE_OUT}/${name}.xml"
            -DEXPECT_EXIT=${expect_exit} "-DEXPECT=${case}" -DJUNIT=${COMPARE_OUT}/${name}.xml -DSUITES=6
            -P ${CMAKE_SOURCE_DIR}/tests/cmake/check_compare.cmake)
  set_tests_properties(compare.${name} PROPERTIES FIXTURES_REQUIRED "sweep_local_run;lost_job_sweep")
endforeach()

# Bad input: exit status 2 and a message naming the folder, or the file and its key.
function(add_compare_error_test name expect)
  add_test(NAME compare.${name}
    COMMAND ${CMAKE_COMMAND} "-DCOMMAND=$<TARGET_FILE:avsm-compare>;${ARGN}" -DEXPECT_EXIT=2 "-DEXPECT=${expect}"
            -P ${CMAKE_SOURCE_DIR}/tests/cmake/check_compare.cmake)
endfunction()
add_compare_error_test(MissingFolderIsAClearError
  "avsm-compare: error: [^\n]*no_such_base: no such folder \\(BASE: a capture folder or a sweep folder\\)"
  ${COMPARE_OUT}/no_such_base ${COMPARE_OUT}/no_such_new)
add_compare_error_test(UnknownThresholdIsAClearError
  "bad_thresholds.json: unknown key \"image.min_psnr\" \\(known in \"image\": min_psnr_db, max_mean_abs_error\\)"
  --thresholds ${CMAKE_SOURCE_DIR}/tests/data/bad_thresholds.json ${COMPARE_OUT}/Base ${COMPARE_OUT}/Same)
add_compare_error_test(OneFolderIsAClearError "expects two folders, BASE and NEW; got 1" ${COMPARE_OUT}/Base)
