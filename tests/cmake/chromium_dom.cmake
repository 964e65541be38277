# chromium_dump_dom(HTML PROFILE_PARENT OUT): the DOM headless Chromium builds from the
# page HTML (a file path), in OUT. PROFILE_PARENT: where a profile folder of its own goes
# when HOME is unset (Chromium writes one even headless). Chromium's stderr (dbus and
# similar noise) is ignored unless it fails to run. Shared by the report checks
# (check_report.cmake, check_sweep_report.cmake).
function(chromium_dump_dom html profile_parent out)
  find_program(CHROMIUM NAMES chromium chromium-browser)
  if(NOT CHROMIUM)
    message(FATAL_ERROR "chromium not found (neither chromium nor chromium-browser is on PATH): "
                        "install it with tools/install-deps.sh (Debian package 'chromium')")
  endif()
  if(DEFINED ENV{HOME})
    set(profile "$ENV{HOME}/profile")
  else()
    set(profile "${profile_parent}/chromium_profile")
  endif()
  file(MAKE_DIRECTORY "${profile}")
  string(REPLACE " " "%20" url "file://${html}")
  execute_process(COMMAND "${CHROMIUM}" --headless --no-sandbox --disable-gpu --no-first-run
                          --user-data-dir=${profile} --dump-dom "${url}"
                  TIMEOUT 60 RESULT_VARIABLE result OUTPUT_VARIABLE dom ERROR_VARIABLE errors)
  if(NOT result EQUAL 0)
    string(LENGTH "${errors}" errors_length)
    if(errors_length GREATER 4000)
      math(EXPR tail_start "${errors_length} - 4000")
      string(SUBSTRING "${errors}" ${tail_start} -1 errors)
    endif()
    message(FATAL_ERROR "${CHROMIUM} --dump-dom ${url} failed (${result}):\n${errors}")
  endif()
  if(NOT dom MATCHES "</html>")
    message(FATAL_ERROR "${CHROMIUM} printed no DOM for ${url}")
  endif()
  set(${out} "${dom}" PARENT_SCOPE)
endfunction()

# Appends to the caller's list `missing` an entry for each of the ids (after DOM) that
# no element of DOM has.
function(require_element_ids dom)
  foreach(id IN LISTS ARGN)
    string(FIND "${dom}" "id=\"${id}\"" at)
    if(at EQUAL -1)
      list(APPEND missing "an element with id=\"${id}\"")
    endif()
  endforeach()
  set(missing "${missing}" PARENT_SCOPE)
endfunction()

# Fails listing what the caller's `missing` holds, if anything.
function(fail_if_missing report)
  if(missing)
    list(JOIN missing "\n  " missing_text)
    message(FATAL_ERROR "${report} as rendered by Chromium lacks:\n  ${missing_text}")
  endif()
endfunction()

# Sets COUNT_VAR to how often PATTERN (no ';': MATCHALL returns a list) matches TEXT and
# appends WHAT to the caller's `missing`, with both counts, unless that is EXPECTED.
function(require_count text pattern expected what count_var)
  string(REGEX MATCHALL "${pattern}" matches "${text}")
  list(LENGTH matches count)
  if(NOT count EQUAL expected)
    list(APPEND missing "${what} (expected ${expected}, found ${count})")
  endif()
  set(missing "${missing}" PARENT_SCOPE)
  set(${count_var} ${count} PARENT_SCOPE)
endfunction()
