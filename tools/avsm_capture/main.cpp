// avsm-capture: renders a scene headless and writes images and per-pass timings.
// The command line is engine/capture/capture_args.h's (which avsm-sweep writes too).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "capture/capture.h"
#include "capture/capture_args.h"
#include "passes/shadows/techniques/techniques.h"

int main(int argc, char** argv) {
  using namespace avsm::capture;
  CaptureCommand command;
  try {
    command = parse_capture_arguments(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::fprintf(stderr, "avsm-capture: %s\n%s", e.what(), capture_usage().c_str());
    return 2;
  }
  if (command.action == CaptureAction::help) {
    std::printf("%s", capture_usage().c_str());
    return 0;
  }
  if (command.action == CaptureAction::list_techniques) {  // for scripts: one registered technique name per line
    for (const avsm::passes::ShadowTechnique* t : avsm::passes::shadow_techniques())
      std::printf("%.*s\n", int(t->name().size()), t->name().data());
    return 0;
  }
  const CaptureOptions& options = command.options;
  try {
    CaptureOutputs out = run_capture(options);
    if (!out.pass_list.empty()) {  // --dump-passes: nothing was rendered
      std::printf("passes:  %s\n", out.pass_list.c_str());
      return 0;
    }
    std::printf("image:   %s\nhdr:     %s\ntimings: %s\n", out.png.c_str(), out.exr.c_str(), out.timings.c_str());
    if (!out.quality.empty()) std::printf("quality: %s\n", out.quality.c_str());
    if (!out.volume_quality.empty()) std::printf("volume quality: %s\n", out.volume_quality.c_str());
    for (const auto& curve : out.curves) std::printf("curve:   %s\n", curve.c_str());
    if (options.report) std::printf("report:  %s\n", (options.out_dir / "report.html").c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avsm-capture: error: %s\n", e.what());
    return 1;
  }
}
