// The gate's two outputs: the text summary (stdout) and JUnit XML (--junit FILE).
#include <algorithm>
#include <array>
#include <sstream>

#include "capture/report.h"
#include "sweep/compare.h"

namespace avsm::sweep {
namespace {

const char* verdict_text(Verdict verdict) {
  switch (verdict) {
    case Verdict::pass: return "ok";
    case Verdict::fail: return "FAIL";
    case Verdict::listed: return "-";
  }
  return "?";
}

size_t count(const SuiteResult& suite, Verdict verdict) {
  return size_t(std::count_if(suite.checks.begin(), suite.checks.end(),
                              [&](const Check& check) { return check.verdict == verdict; }));
}

// One row of the table per check; the columns as wide as their longest cell.
void write_table(std::ostream& out, const SuiteResult& suite) {
  using Row = std::array<std::string, 6>;
  std::vector<Row> rows{{"check", "BASE", "NEW", "change", "limit", "result"}};
  for (const Check& c : suite.checks)
    rows.push_back({c.name, c.base, c.now, c.change, c.limit,
                    c.verdict == Verdict::listed ? "- " + c.message : verdict_text(c.verdict)});
  std::array<size_t, 6> width{};
  for (const Row& row : rows)
    for (size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
  for (const Row& row : rows) {
    std::string line;
    for (size_t i = 0; i < row.size(); ++i)
      line += i + 1 < row.size() ? row[i] + std::string(width[i] - row[i].size() + 2, ' ') : row[i];
    out << "  " << line << "\n";
  }
}

// Text for XML attributes and content: the markup characters escaped, and characters
// XML 1.0 cannot hold at all (controls other than tab and newline) as '?'.
std::string xml_escaped(const std::string& text) {
  std::string printable = text;
  for (char& ch : printable)
    if (static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n') ch = '?';
  return capture::escape_markup(printable);
}

std::string figures(const Check& c) {
  return "BASE " + (c.base.empty() ? "-" : c.base) + ", NEW " + (c.now.empty() ? "-" : c.now) + ", change " +
         (c.change.empty() ? "-" : c.change) + ", limit " + (c.limit.empty() ? "-" : c.limit);
}

}  // namespace

std::string summary_text(const GateResult& result) {
  std::ostringstream out;
  out << "avsm-compare: BASE " << result.base << "\n              NEW  " << result.now << "\n";
  for (const SuiteResult& suite : result.suites) {
    out << "\n" << suite.name << ": " << suite.checks.size() << (suite.checks.size() == 1 ? " check, " : " checks, ")
        << suite.failures() << " failed\n";
    write_table(out, suite);
  }
  const size_t failures = result.failures();
  out << "\n";
  if (failures == 0) {
    out << "PASS: no threshold crossed\n";
    return out.str();
  }
  out << "FAIL: " << failures << (failures == 1 ? " check" : " checks") << " crossed a threshold\n";
  for (const SuiteResult& suite : result.suites)
    for (const Check& check : suite.checks)
      if (check.verdict == Verdict::fail) out << "  " << suite.name << ": " << check.message << "\n";
  return out.str();
}

std::string junit_xml(const GateResult& result) {
  size_t tests = 0, skipped = 0;
  for (const SuiteResult& suite : result.suites) tests += suite.checks.size(), skipped += count(suite, Verdict::listed);
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"avsm-compare\" tests=\"" << tests << "\" failures=\"" << result.failures()
      << "\" errors=\"0\" skipped=\"" << skipped << "\">\n";
  for (const SuiteResult& suite : result.suites) {
    const std::string name = xml_escaped(suite.name);
    out << "  <testsuite name=\"" << name << "\" tests=\"" << suite.checks.size() << "\" failures=\""
        << suite.failures() << "\" errors=\"0\" skipped=\"" << count(suite, Verdict::listed) << "\">\n";
    for (const Check& check : suite.checks) {
      out << "    <testcase classname=\"" << name << "\" name=\"" << xml_escaped(check.name) << "\">\n";
      if (check.verdict == Verdict::fail)
        out << "      <failure type=\"threshold\" message=\"" << xml_escaped(check.message) << "\">"
            << xml_escaped(figures(check)) << "</failure>\n";
      if (check.verdict == Verdict::listed)
        out << "      <skipped message=\"" << xml_escaped(check.message) << "\"/>\n";
      out << "      <system-out>" << xml_escaped(figures(check)) << "</system-out>\n"
          << "    </testcase>\n";
    }
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
  return out.str();
}

}  // namespace avsm::sweep
