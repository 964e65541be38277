// avsm-ltc-fit: fits the engine's GGX lobe with linearly transformed cosines
// (engine/lighting/ltc.h) and writes the table as C++ source, the file the engine compiles
// in (engine/lighting/ltc_ggx_table.inc). Exit 0 written, 1 bad usage or a failure.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <numeric>
#include <string>

#include "lighting/ltc.h"

namespace {

const char* kUsage =
    "usage: avsm-ltc-fit --out FILE [--size N] [--threads N]\n"
    "  --out FILE     the table as C++ source (the engine's is engine/lighting/ltc_ggx_table.inc)\n"
    "  --size N       N x N entries over (roughness, view angle), %u to %u (default %u)\n"
    "  --threads N    rows fitted at once (default: one per hardware thread); the table\n"
    "                 does not depend on it\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "avsm-ltc-fit: error: %s\n", message.c_str());
  std::exit(1);
}

uint32_t whole_number(const std::string& flag, const std::string& text, uint32_t min, uint32_t max) {
  const std::string expected = flag + " expects a whole number from " + std::to_string(min) + " to " +
                               std::to_string(max) + ", got '" + text + "'";
  if (text.empty() || text.size() > 9 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    usage_error(expected);
  const unsigned long value = std::stoul(text);
  if (value < min || value > max) usage_error(expected);
  return uint32_t(value);
}

struct Options {
  std::string out;
  uint32_t size = avsm::lighting::kLtcDefaultTableSize;
  uint32_t threads = 0;
  std::string arguments;  // as given, for the file's header
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    options.arguments += (i > 1 ? " " : "") + arg;
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(arg + " expects a value");
      options.arguments += std::string(" ") + argv[i + 1];
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf(kUsage, avsm::lighting::kLtcMinTableSize, avsm::lighting::kLtcMaxTableSize,
                  avsm::lighting::kLtcDefaultTableSize);
      std::exit(0);
    } else if (arg == "--out") {
      options.out = value();
    } else if (arg == "--size") {
      options.size = whole_number(arg, value(), avsm::lighting::kLtcMinTableSize, avsm::lighting::kLtcMaxTableSize);
    } else if (arg == "--threads") {
      options.threads = whole_number(arg, value(), 1, 1024);
    } else {
      usage_error("unknown argument '" + arg + "' (--help lists the options)");
    }
  }
  if (options.out.empty()) usage_error("--out FILE is required (the table's C++ source)");
  // Before a fit of a minute, not after it.
  const std::filesystem::path folder = std::filesystem::path(options.out).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
    usage_error("--out " + options.out + ": there is no folder '" + folder.string() + "'");
  return options;
}

// Max and mean fit error over all entries, and per quarter of the roughness range.
void print_summary(const avsm::lighting::LtcTable& table, const avsm::lighting::LtcFitReport& report) {
  const auto summarise = [&](const char* label, uint32_t first_row, uint32_t end_row) {
    const auto begin = report.fit_error.begin() + ptrdiff_t(table.index(first_row, 0));
    const auto end = report.fit_error.begin() + ptrdiff_t(table.index(end_row, 0));
    const double max = *std::max_element(begin, end);
    const double mean = std::accumulate(begin, end, 0.0) / double(end - begin);
    std::printf("  %-28s max %.4f  mean %.4f\n", label, max, mean);
  };
  std::printf("fit error (share of the lobe's energy the LTC puts elsewhere):\n");
  summarise("all", 0, table.size);
  for (uint32_t quarter = 0; quarter < 4 && table.size >= 4; ++quarter) {
    const uint32_t first = quarter * table.size / 4, end = (quarter + 1) * table.size / 4;
    char label[64];
    std::snprintf(label, sizeof label, "roughness %.2f to %.2f",
                  double(avsm::lighting::ltc_row_roughness(table.size, first)),
                  double(avsm::lighting::ltc_row_roughness(table.size, end - 1)));
    summarise(label, first, end);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  try {
    avsm::lighting::LtcFitReport report;
    const avsm::lighting::LtcTable table = avsm::lighting::fit_ggx_table(options.size, options.threads, &report);
    avsm::lighting::write_table_source(table, options.out, "avsm-ltc-fit " + options.arguments);
    std::printf("avsm-ltc-fit: %ux%u entries in %.1f s, written to %s\n", table.size, table.size, report.seconds,
                options.out.c_str());
    print_summary(table, report);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avsm-ltc-fit: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
