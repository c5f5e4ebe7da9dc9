// JUnit XML of compare reports (report.h): what every CI shows natively. Valid against both common
// schemas (Jenkins xunit's junit-10.xsd and the stricter Ant JUnit.xsd; tests/data/junit validates):
// failures are failing quantities, errors the inputs that could not be compared, times measured.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>

#include "views/capture/image_io.h"
#include "views/report/report.h"

namespace gb {

namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;  // XML 1.0 allows no other controls
    }
  }
  return out;
}

std::string attr(const char* name, const std::string& value) { return std::string(" ") + name + "=\"" + escape(value) + "\""; }
std::string attr(const char* name, uint64_t value) { return attr(name, std::to_string(value)); }

struct Case {
  std::string name, message;
  enum class Is { Pass, Warn, Fail, Skip, Error } is = Is::Pass;
  double seconds = 0.0;
};

Case::Is caseOf(Verdict v) { return v == Verdict::Fail ? Case::Is::Fail : v == Verdict::Warn ? Case::Is::Warn : Case::Is::Pass; }

// One case per mismatched or skipped target, compared group and FLIP entry, with its report lines; a
// pair that could not be compared is one errored case ("compare": the inputs, not a quantity, failed).
std::vector<Case> casesOf(const CompareReport& r) {
  std::vector<Case> cases;
  if (!r.error.empty()) cases.push_back({"compare", r.error, Case::Is::Error, r.seconds});
  for (auto& [target, why] : r.mismatches) cases.push_back({target, "MISMATCH " + target + ": " + why, Case::Is::Fail});
  for (auto& [target, why] : r.skipped) cases.push_back({target, why, Case::Is::Skip});
  for (const GroupResult& g : r.groups) cases.push_back({g.group.key, groupText(g), caseOf(g.verdict), g.seconds});
  for (const FlipResult& f : r.flips) cases.push_back({"flip." + f.target, flipText(f), caseOf(f.verdict), f.seconds});
  return cases;
}

std::string utcNow() {
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%S", std::gmtime(&t));
  return buf;
}

// Seconds as both schemas take them (xs:decimal; junit-10.xsd's Surefire pattern): fixed point, no
// exponent, at most three decimals.
std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", std::max(0.0, s));
  return buf;
}

std::string property(const std::string& name, const std::string& value) {
  return "      <property" + attr("name", name) + attr("value", value) + "/>\n";
}

std::string caseXml(const Case& c, const std::string& classname) {
  std::string x = "    <testcase" + attr("name", c.name) + attr("classname", classname) + attr("time", seconds(c.seconds));
  auto child = [&](const char* element, const char* type) {
    return ">\n      <" + std::string(element) + attr("message", c.message) + attr("type", type) + ">" + escape(c.message) +
           "</" + element + ">\n    </testcase>\n";
  };
  switch (c.is) {
    case Case::Is::Fail: return x + child("failure", "gblens.compare.fail");
    case Case::Is::Error: return x + child("error", "gblens.compare.file_error");
    case Case::Is::Skip: return x + ">\n      <skipped" + attr("message", c.message) + "/>\n    </testcase>\n";
    default: return x + "/>\n";  // passed or warned (the warning is a property and in <system-out>)
  }
}

// One <testsuite>. The Ant schema fixes the children's order (properties, testcases, system-out,
// system-err) and allows a test case no output of its own, so warnings are suite properties
// ("warning.KEY", read by Jenkins, GitLab and Azure as the suite's) and the first lines of its
// <system-out>.
std::string suiteXml(const std::string& suite, int id, const CompareReport& report, const std::vector<Case>& cases,
                     const std::string& host) {
  uint64_t f = 0, e = 0, s = 0, w = 0;
  std::string props = property("a", report.a) + property("b", report.b) + property("exit_code", std::to_string(report.exitCode));
  std::string warnings, body;
  for (const Case& c : cases) {
    f += c.is == Case::Is::Fail, e += c.is == Case::Is::Error, s += c.is == Case::Is::Skip, w += c.is == Case::Is::Warn;
    if (c.is == Case::Is::Warn) {
      props += property("warning." + c.name, c.message);
      warnings += "WARNING " + c.message;
    }
    body += caseXml(c, "gblens.compare." + suite);
  }
  props += property("warnings", std::to_string(w));
  const std::string text = report.error.empty() ? report.text() : "gblens compare\n  A " + report.a + "\n  B " + report.b +
                                                                      "\nFILE ERROR: " + report.error + "\n";
  return "  <testsuite" + attr("name", suite) + attr("id", std::to_string(id)) + attr("package", "gblens.compare") +
         attr("tests", cases.size()) + attr("failures", f) + attr("errors", e) + attr("skipped", s) +
         attr("time", seconds(report.seconds)) + attr("timestamp", utcNow()) + attr("hostname", host) + ">\n" +
         "    <properties>\n" + props + "    </properties>\n" + body + "    <system-out>" + escape(warnings + text) +
         "</system-out>\n    <system-err></system-err>\n  </testsuite>\n";
}

}  // namespace

std::string junitXml(const std::vector<NamedReport>& reports) {
  char host[256] = "localhost";
  gethostname(host, sizeof(host) - 1);
  std::string suites;
  int id = 0;
  for (auto& [name, report] : reports)
    suites += suiteXml(name.empty() ? "gblens compare" : name, id++, *report, casesOf(*report), host);
  // <testsuites> carries no attributes: the Ant schema allows none (readers sum the suites).
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n" + suites + "</testsuites>\n";
}

bool writeJunit(const std::vector<NamedReport>& reports, const std::string& file, std::string& error) {
  const std::string xml = junitXml(reports);
  const bool ok = writeAtomically(file, ".xml", [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << xml;
    return bool(out.flush());
  });
  if (!ok) error = "--junit " + file + ": cannot write";
  return ok;
}

}  // namespace gb
