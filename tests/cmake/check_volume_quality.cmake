# Checks DIR/volume_quality.json (avsm-capture --compare-volume-shading): enough smoke
# pixels to judge by, and the fast shading within the bound against the reference
# (mean |dL| <= 2%, 99th percentile <= 10% of the mean luminance). With
# -DEXPECT_OUTSIDE=ON the shading compared must fall outside the bound instead (the
# check's own test: volumes hidden from the camera are far from the reference).
file(READ "${DIR}/volume_quality.json" quality)
string(JSON pixels GET "${quality}" smoke_pixels)
string(JSON mean GET "${quality}" mean_relative)
string(JSON p99 GET "${quality}" p99_relative)
string(JSON within GET "${quality}" within_bound)
string(JSON settings GET "${quality}" fast_settings)
message(STATUS "${settings}: ${pixels} smoke pixels, mean |dL| ${mean}, p99 ${p99} of the mean luminance")
if(pixels LESS 200)
  message(FATAL_ERROR "volume_quality.json: only ${pixels} smoke pixels; the camera must see the smoke")
endif()
foreach(file volume_error.png frame_reference.exr)
  if(NOT EXISTS "${DIR}/${file}")
    message(FATAL_ERROR "${DIR}/${file} is missing")
  endif()
endforeach()
if(EXPECT_OUTSIDE)
  if(within)
    message(FATAL_ERROR "expected this shading outside the bound (mean ${mean}, p99 ${p99})")
  endif()
elseif(NOT within)
  message(FATAL_ERROR "the fast volume shading is outside the bound: mean |dL| ${mean} (bound 0.02), p99 ${p99} (bound 0.10)")
endif()
