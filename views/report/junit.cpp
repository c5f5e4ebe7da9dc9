// JUnit XML of compare reports (report.h): what every CI shows natively. The elements and attributes
// follow the common JUnit schemas (Jenkins' junit-10.xsd; the stricter Ant/windyroad JUnit.xsd's
// required ones too: timestamp, hostname, time, properties, system-out, system-err).
#include <unistd.h>

#include <chrono>
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
  enum class Is { Pass, Fail, Skip } is = Is::Pass;
};

// One case per mismatched or skipped target, compared group and FLIP entry, with its report lines.
std::vector<Case> casesOf(const CompareReport& r) {
  std::vector<Case> cases;
  for (auto& [target, why] : r.mismatches) cases.push_back({target, "MISMATCH " + target + ": " + why, Case::Is::Fail});
  for (auto& [target, why] : r.skipped) cases.push_back({target, why, Case::Is::Skip});
  for (const GroupResult& g : r.groups)
    cases.push_back({g.group.key, groupText(g), g.verdict == Verdict::Fail ? Case::Is::Fail : Case::Is::Pass});
  for (const FlipResult& f : r.flips)
    cases.push_back({"flip." + f.target, flipText(f), f.verdict == Verdict::Fail ? Case::Is::Fail : Case::Is::Pass});
  return cases;
}

std::string utcNow() {
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%S", std::gmtime(&t));
  return buf;
}

}  // namespace

std::string junitXml(const std::vector<NamedReport>& reports) {
  char host[256] = "localhost";
  gethostname(host, sizeof(host) - 1);
  std::string suites;
  uint64_t tests = 0, failures = 0, skipped = 0;
  int id = 0;
  for (auto& [name, report] : reports) {
    const std::string suite = name.empty() ? "gblens compare" : name;
    const std::vector<Case> cases = casesOf(*report);
    uint64_t f = 0, s = 0;
    std::string body;
    for (const Case& c : cases) {
      f += c.is == Case::Is::Fail;
      s += c.is == Case::Is::Skip;
      body += "    <testcase" + attr("name", c.name) + attr("classname", "gblens.compare." + suite) + attr("time", "0");
      if (c.is == Case::Is::Fail)
        body += ">\n      <failure" + attr("message", c.message) + attr("type", "gblens.compare") + ">" +
                escape(c.message) + "</failure>\n    </testcase>\n";
      else if (c.is == Case::Is::Skip)
        body += ">\n      <skipped" + attr("message", c.message) + "/>\n    </testcase>\n";
      else
        body += ">\n      <system-out>" + escape(c.message) + "</system-out>\n    </testcase>\n";
    }
    suites += "  <testsuite" + attr("name", suite) + attr("id", uint64_t(id++)) + attr("package", "gblens.compare") +
              attr("tests", cases.size()) + attr("failures", f) + attr("errors", uint64_t(0)) + attr("skipped", s) +
              attr("time", "0") + attr("timestamp", utcNow()) + attr("hostname", host) + ">\n" +
              "    <properties>\n      <property" + attr("name", "a") + attr("value", report->a) + "/>\n      <property" +
              attr("name", "b") + attr("value", report->b) + "/>\n      <property" + attr("name", "exit_code") +
              attr("value", std::to_string(report->exitCode)) + "/>\n    </properties>\n" + body +
              "    <system-out>" + escape(report->text()) + "</system-out>\n    <system-err></system-err>\n  </testsuite>\n";
    tests += cases.size(), failures += f, skipped += s;
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites" + attr("name", "gblens compare") + attr("tests", tests) +
         attr("failures", failures) + attr("errors", uint64_t(0)) + attr("skipped", skipped) + attr("time", "0") + ">\n" +
         suites + "</testsuites>\n";
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
