# Opens DIR/report.html (avsm-capture --report) in headless Chromium, dumps the DOM it
# built and checks that the report's elements are there: every section id, the embedded
# PNGs, one bar (<rect>) per pass of timings.json in the timing chart, one light-map
# image per light*_transmittance.png in DIR and one memory row per light of memory.json;
# the shadow-quality table and images when quality.json is there, and the texel curves.
set(report "${DIR}/report.html")
if(NOT EXISTS "${report}")
  message(FATAL_ERROR "missing ${report}: did avsm-capture --report run?")
endif()
include("${CMAKE_CURRENT_LIST_DIR}/chromium_dom.cmake")
chromium_dump_dom("${report}" "${DIR}" dom)

set(missing "")
require_element_ids("${dom}" frame-image timing-chart frame-summary memory-table light-images graph-passes graph-resources
                    graph-dot)

if(NOT dom MATCHES "<img[^>]*src=\"data:image/png;base64,")
  list(APPEND missing "an <img> with a data:image/png;base64 source")
endif()
if(NOT dom MATCHES "<img[^>]*id=\"frame-image\"[^>]*src=\"data:image/png;base64,")
  list(APPEND missing "the frame image (<img id=\"frame-image\">) embedded as data:image/png;base64")
endif()

# The timing chart: an <svg id="timing-chart"> with one <rect> per pass in timings.json.
file(READ "${DIR}/timings.json" timings)
string(JSON pass_count LENGTH "${timings}" passes)
string(REGEX MATCH "<svg[^>]*id=\"timing-chart\".*" chart "${dom}")
if(NOT chart)
  list(APPEND missing "an <svg id=\"timing-chart\">")
else()
  string(FIND "${chart}" "</svg>" chart_end)
  if(chart_end EQUAL -1)
    list(APPEND missing "the end of the timing chart </svg>")
  else()
    string(SUBSTRING "${chart}" 0 ${chart_end} chart)
  endif()
  require_count("${chart}" "<rect[ />]" ${pass_count} "one <rect> per pass of timings.json in the timing chart" bar_count)
endif()

# Every light*_transmittance.png in the folder, as an <img class="light-map">.
file(GLOB light_files "${DIR}/light*_transmittance.png")
list(LENGTH light_files light_file_count)
require_count("${dom}" "<img[^>]*class=\"light-map\"" ${light_file_count}
              "one <img class=\"light-map\"> per light*_transmittance.png" light_image_count)

# The memory table: a row per light of memory.json.
file(READ "${DIR}/memory.json" memory)
string(JSON light_count LENGTH "${memory}" lights)
require_count("${dom}" "<tr class=\"light\">" ${light_count} "one memory-table row per light of memory.json"
              light_row_count)

# With --compare-to uncompressed: the quality table, one error image per light of
# quality.json; with --plot-texel: one <img class="texel-curve"> per curve_*.svg.
if(EXISTS "${DIR}/quality.json")
  file(READ "${DIR}/quality.json" quality)
  string(JSON quality_lights LENGTH "${quality}" lights)
  string(FIND "${dom}" "id=\"quality-table\"" at)
  if(at EQUAL -1)
    list(APPEND missing "an element with id=\"quality-table\" (quality.json is in the folder)")
  endif()
  require_count("${dom}" "<img[^>;]*class=\"error-image\"" ${quality_lights}
                "one <img class=\"error-image\"> per light of quality.json" error_image_count)
  if(quality_lights GREATER 0 AND NOT dom MATCHES "class=\"error-image\"[^>]*src=\"data:image/png;base64,")
    list(APPEND missing "the error images embedded as data:image/png;base64")
  endif()
endif()
file(GLOB curve_files "${DIR}/curve_*.svg")
list(LENGTH curve_files curve_file_count)
require_count("${dom}" "<img[^>;]*class=\"texel-curve\"" ${curve_file_count}
              "one <img class=\"texel-curve\"> per curve_*.svg" curve_image_count)
if(curve_file_count GREATER 0 AND NOT dom MATCHES "class=\"texel-curve\"[^>]*src=\"data:image/svg\\+xml;base64,")
  list(APPEND missing "the texel curves embedded as data:image/svg+xml;base64")
endif()

fail_if_missing("${report}")
string(LENGTH "${dom}" dom_length)
message(STATUS "report.html OK: ${pass_count} timing bars, ${light_image_count} light images, ${light_count} lights, "
               "${dom_length} characters of DOM")
