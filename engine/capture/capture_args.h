#pragma once
// avsm-capture's command line, both ways, in one place: parse_capture_arguments() is
// what the tool runs; capture_arguments() writes the flags that give a CaptureOptions
// back (what a sweep runs each job's avsm-capture with).
#include <stdexcept>
#include <string>
#include <vector>

#include "capture/capture.h"

namespace avsm::capture {

// A bad command line: what() names the flag and what it expects (no usage text).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CaptureAction { capture, help, list_techniques };

struct CaptureCommand {
  CaptureAction action = CaptureAction::capture;  // --help and --list-techniques stop the parse
  CaptureOptions options;
};

// The arguments after the program name. Throws UsageError.
CaptureCommand parse_capture_arguments(const std::vector<std::string>& args);

// The flags for every option that differs from CaptureOptions{}, in a fixed order, such
// that parse_capture_arguments(capture_arguments(o)).options == o for any o it accepts.
std::vector<std::string> capture_arguments(const CaptureOptions& options);

// Throws UsageError when avsm-capture would refuse `options` (a value out of range,
// an unknown technique, options that exclude each other).
void validate_capture_options(const CaptureOptions& options);

// The --help text: the options, then every registered shadow technique with its parameters.
std::string capture_usage();

}  // namespace avsm::capture
