#pragma once
// The capture report: one self-contained HTML file (no external resources, no
// script) drawn from the capture's FrameReport (capture/frame_report.h) and the
// images run_capture wrote into its output folder: the frame and any per-light
// transmittance images, a per-pass GPU timing chart, the frame summary, the memory
// figures and the compiled frame graph. What --report writes.
#include <filesystem>

#include "capture/frame_report.h"
#include "capture/html.h"  // escape_markup, for callers that write markup of their own

namespace avsm::capture {

// Shows `report`; embeds frame.png (required: std::runtime_error naming it when
// missing or unreadable), and light*_transmittance.png, the quality error images
// and curve_*.svg from out_dir when present; writes html_path.
void write_report(const std::filesystem::path& out_dir, const FrameReport& report,
                  const std::filesystem::path& html_path);

}  // namespace avsm::capture
