// avsm-compare: the regression gate. Compares two capture folders or two sweep
// folders (engine/sweep/compare.h); exit 0 pass, 1 a check failed (a threshold crossed, or
// settings that differ without --allow-different-settings), 2 bad usage or input.
#include <cstdio>
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "capture/files.h"
#include "sweep/compare.h"

namespace {

const char* kUsage =
    "usage: avsm-compare BASE NEW [--thresholds FILE] [--junit FILE] [--allow-different-settings]\n"
    "  BASE, NEW           two capture folders (avsm-capture --out) or two sweep folders\n"
    "                      (avsm-sweep --out; jobs matched by id)\n"
    "  --thresholds FILE   JSON overriding some of the default thresholds (docs/farm.md,\n"
    "                      \"Regression gate\"); the defaults:\n"
    "%s\n"
    "  --junit FILE        also write the checks as JUnit XML (one testsuite per job)\n"
    "  --allow-different-settings\n"
    "                      list the settings that differ between BASE and NEW (settings.json:\n"
    "                      technique, nodes, resolution, scene, image size...) instead of\n"
    "                      failing on them, and compare the figures anyway\n"
    "exit status: 0 every check passed, 1 a check failed (a threshold crossed, or settings\n"
    "that differ), 2 bad usage or input\n";

void print_usage(std::FILE* to) {
  const std::string defaults = avsm::sweep::to_json(avsm::sweep::Thresholds{}).dump(2);
  std::fprintf(to, kUsage, defaults.c_str());
}

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "avsm-compare: %s\n", message.c_str());
  print_usage(stderr);
  std::exit(2);
}

struct Options {
  std::vector<std::string> folders;
  std::optional<std::string> thresholds, junit;
  avsm::sweep::CompareOptions compare;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " expects a file");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      std::exit(0);
    } else if (arg == "--thresholds") {
      options.thresholds = value();
    } else if (arg == "--junit") {
      options.junit = value();
    } else if (arg == "--allow-different-settings") {
      options.compare.allow_different_settings = true;
    } else if (arg.rfind("--", 0) == 0) {
      usage_error("unknown option '" + arg + "'");
    } else {
      options.folders.push_back(arg);
    }
  }
  if (options.folders.size() != 2)
    usage_error("expects two folders, BASE and NEW; got " + std::to_string(options.folders.size()));
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  try {
    const avsm::sweep::Thresholds limits =
        options.thresholds ? avsm::sweep::read_thresholds(*options.thresholds) : avsm::sweep::Thresholds{};
    const avsm::sweep::GateResult result = avsm::sweep::compare_folders(options.folders[0], options.folders[1], limits, options.compare);
    std::cout << avsm::sweep::summary_text(result) << std::flush;
    if (options.junit) avsm::capture::write_text(*options.junit, avsm::sweep::junit_xml(result));
    return result.failures() ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avsm-compare: error: %s\n", e.what());
    return 2;
  }
}
