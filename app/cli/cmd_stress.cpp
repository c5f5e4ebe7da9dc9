// gblens stress: the numerical stability torture suite (views/stress.h). Runs every case (or
// --case NAME), prints each case's bounds before it runs and its progress on stderr, then the
// table on stdout; --json FILE writes the table; exits 1 when any bound is not met.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "app/cli/cli.h"
#include "app/stress/stress.h"

namespace gb {

namespace {

struct StressOptions {
  std::vector<std::string> cases;
  std::string json;
  bool quick = false, list = false, validate = false;
  std::string device;
};

bool writeJsonAtomically(const std::string& path, const nlohmann::json& j, std::string& error) {
  std::filesystem::path target(path), tmp = target;
  tmp += ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) {
      error = "--json " + path + ": cannot write the file";
      return false;
    }
    out << j.dump(2) << "\n";
    if (!out) {
      error = "--json " + path + ": write failed";
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, target, ec);
  if (ec) error = "--json " + path + ": " + ec.message();
  return !ec;
}

int runStress(const StressOptions& so) {
  const std::vector<stress::Case>& all = stress::cases();
  if (so.list) {
    for (const stress::Case& c : all) std::printf("%-20s %s\n", c.name.c_str(), c.description.c_str());
    return 0;
  }
  std::vector<const stress::Case*> chosen;
  for (const std::string& name : so.cases) {
    const stress::Case* found = nullptr;
    for (const stress::Case& c : all) found = c.name == name ? &c : found;
    if (!found) {
      std::string names;
      for (const stress::Case& c : all) names += (names.empty() ? "" : ", ") + c.name;
      std::fprintf(stderr, "gblens stress: --case %s: no such case (cases: %s)\n", name.c_str(), names.c_str());
      return 2;
    }
    chosen.push_back(found);
  }
  if (chosen.empty())
    for (const stress::Case& c : all) chosen.push_back(&c);

  HeadlessSession session({so.device, so.validate, true});
  stress::Context sc;
  sc.session = &session;
  sc.quick = so.quick;
  std::fprintf(stderr, "gblens stress on %s (%s run, %zu case(s))\n", session.deviceName().c_str(), so.quick ? "quick" : "full",
               chosen.size());
  auto suiteStart = std::chrono::steady_clock::now();
  for (size_t i = 0; i < chosen.size(); ++i) {
    const stress::Case& c = *chosen[i];
    std::fprintf(stderr, "[%zu/%zu] %s: %s\n", i + 1, chosen.size(), c.name.c_str(), c.description.c_str());
    sc.caseName = c.name;
    sc.stated.clear();
    auto start = std::chrono::steady_clock::now();
    c.run(sc);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    bool scanned = false;
    for (const stress::Row& r : sc.rows) scanned |= r.caseName == c.name && r.metric == "NaN/Inf texels, all targets";
    if (!scanned) stress::addScan(sc, {}, c.name);  // a case that scanned nothing still states its 0
    for (stress::Row& r : sc.rows)
      if (r.caseName == c.name && r.metric == "NaN/Inf texels, all targets")
        std::fprintf(stderr, "  %-4s NaN/Inf texels, all targets: %.0f\n", r.pass ? "ok" : "FAIL", r.measured);
    std::fprintf(stderr, "  (%.1f s)\n", seconds);
  }
  double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - suiteStart).count();
  int failed = 0;
  for (const stress::Row& r : sc.rows) failed += !r.pass;
  stress::printTable(sc.rows);
  std::printf("%d of %zu checks failed (%.1f s, %s)\n", failed, sc.rows.size(), total, session.deviceName().c_str());
  int status = failed ? 1 : 0;
  if (!so.json.empty()) {
    nlohmann::json j = {{"device", session.deviceName()},
                        {"run", so.quick ? "quick" : "full"},
                        {"command", commandLine()},
                        {"seconds", total},
                        {"failed", failed},
                        {"rows", stress::tableJson(sc.rows)}};
    std::string error;
    if (!writeJsonAtomically(so.json, j, error)) {
      std::fprintf(stderr, "gblens stress: %s\n", error.c_str());
      status = 2;
    }
  }
  if (session.reportValidation() && status == 0) status = 1;
  return status;
}

}  // namespace

Command addStressCommand(CLI::App& root) {
  auto so = std::make_shared<StressOptions>();
  CLI::App* cmd = root.add_subcommand("stress", "numerical stability torture suite with stated bounds (exit 1 on a failure)");
  cmd->add_option("--case", so->cases, "run only this case (repeatable; --list names them)");
  cmd->add_option("--json", so->json, "write the table as JSON to FILE");
  cmd->add_flag("--quick", so->quick, "reduced sizes (CTest)");
  cmd->add_flag("--list", so->list, "list the cases and exit");
  cmd->add_option("--device", so->device, "Vulkan device by name or index (default: first GPU, else CPU)");
  cmd->add_flag("--validate", so->validate, "enable Vulkan validation layers; non-zero exit on any message");
  return {cmd, [so]() { return runStress(*so); }};
}

}  // namespace gb
