// `gblens compare --pairs LIST` (report.h): many pairs compared with one set of settings, one page per
// pair under the report folder and an index page, one JUnit file and one JSON file for all of them.
// Pairs are compared one at a time; only their figures stay in memory.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "views/capture/image_io.h"
#include "views/report/report.h"
#include "views/report/report_internal.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

struct Pair {
  std::string a, b, name;
  int line = 0;
};

// Reads LIST: "A B [NAME]" a line, '#' comments; paths relative to LIST's folder. Names must be
// unique folder names (default: pair1, pair2, ...).
bool readPairs(const std::string& list, std::vector<Pair>& pairs, std::string& error) {
  std::ifstream in(list);
  if (!in) {
    error = "--pairs " + list + ": cannot read";
    return false;
  }
  const fs::path base = fs::path(list).parent_path();
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    if (size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    Pair p;
    p.line = n;
    if (!(words >> p.a)) continue;
    std::string extra;
    if (!(words >> p.b) || ((words >> p.name) && (words >> extra))) {
      error = "--pairs " + list + " line " + std::to_string(n) + ": expected 'A B [NAME]'";
      return false;
    }
    if (p.name.empty()) p.name = "pair" + std::to_string(pairs.size() + 1);
    if (compareFileName(p.name, "").empty() || p.name == "img" || p.name == "data") {
      error = "--pairs " + list + " line " + std::to_string(n) + ": NAME \"" + p.name + "\" must be a plain folder name";
      return false;
    }
    for (const Pair& q : pairs)
      if (q.name == p.name) {
        error = "--pairs " + list + " line " + std::to_string(n) + ": NAME \"" + p.name + "\" used twice";
        return false;
      }
    for (std::string* path : {&p.a, &p.b})
      if (fs::path(*path).is_relative()) *path = (base / *path).lexically_normal().string();
    pairs.push_back(p);
  }
  if (pairs.empty()) error = "--pairs " + list + ": no pairs in it";
  return !pairs.empty();
}

// One pair: compared, its page written into `dir` (when a report is asked for), the figures kept.
struct Done {
  Pair pair;
  CompareReport report;  // errors dropped
  std::string loadError;
  nlohmann::json thumbnails;  // the index page's pictures of it (null: it did not load)
};

void comparePair(const Pair& p, const CompareSettings& settings, const std::string& dir, Done& d, std::string& fatal) {
  d.pair = p;
  const auto started = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
  Capture a, b;
  std::string error;
  if (!loadCapture(p.a, a, error) || !loadCapture(p.b, b, error) || !compare(a, b, settings, d.report, error)) {
    d.loadError = error;
    d.report = CompareReport{};
    d.report.a = p.a, d.report.b = p.b;
    d.report.exitCode = kCompareFileError;
    d.report.error = error;
    d.report.seconds = elapsed();
    return;
  }
  d.report.seconds = elapsed();  // loading both captures too: what the pair cost
  if (!dir.empty()) {
    std::error_code ec;
    fs::create_directories(fs::path(dir) / p.name, ec);
    if (!writeReportContents(a, b, d.report, (fs::path(dir) / p.name).string(), error) ||
        !writeThumbnails(a, d.report, (fs::path(dir) / p.name).string(), p.name + "/", d.thumbnails, error))
      fatal = error;
  }
  for (GroupResult& g : d.report.groups) g.errors = {};
  for (FlipResult& f : d.report.flips) f.errors = {};
  d.report.mask.bits = {};
}

}  // namespace

bool comparePairs(const std::string& list, const CompareSettings& settings, const PairsOutputs& out, PairsRun& run,
                  std::string& error) {
  std::vector<Pair> pairs;
  if (!readPairs(list, pairs, error)) return false;
  std::vector<Done> done(pairs.size());
  auto compareAll = [&](const std::string& dir, std::string& e) {
    for (size_t i = 0; i < pairs.size(); ++i) {
      if (settings.progress) settings.progress(double(i) / double(pairs.size()), "pair " + pairs[i].name);
      comparePair(pairs[i], settings, dir, done[i], e);
      if (!e.empty()) return false;
    }
    nlohmann::json index = nlohmann::json::array();
    for (const Done& d : done) {
      nlohmann::json j = d.report.json();
      index.push_back({{"name", d.pair.name}, {"a", d.pair.a}, {"b", d.pair.b}, {"result", j["result"]},
                       {"exit_code", d.report.exitCode}, {"error", d.loadError},
                       {"page", d.loadError.empty() ? d.pair.name + "/index.html" : ""}, {"groups", j["groups"]},
                       {"flip", j["flip"]}, {"mismatches", j["mismatches"]}, {"thumbnails", d.thumbnails}});
    }
    return dir.empty() || writePage(dir, {{"kind", "index"}, {"pairs", index}}, e);
  };
  const bool ok = out.report.empty()
                      ? compareAll("", error)
                      : replaceDirectory(out.report, "report.js", "compare report", compareAll, error);
  if (!ok) return false;
  std::vector<NamedReport> named;
  nlohmann::json all = nlohmann::json::array();
  for (const Done& d : done) {
    named.push_back({d.pair.name, &d.report});
    nlohmann::json j = d.report.json();
    j["name"] = d.pair.name;
    all.push_back(j);
    run.exitCode = std::max(run.exitCode, d.report.exitCode);
    run.text += d.pair.name + ": " + std::string(j["result"]) + " (exit " + std::to_string(d.report.exitCode) + ")" +
                (d.loadError.empty() ? "" : ": " + d.loadError) + "\n";
  }
  if (!out.junit.empty() && !writeJunit(named, out.junit, error)) return false;
  if (out.json == "-") run.json = all.dump(2) + "\n";
  else if (!out.json.empty() && !writeTextAtomically(out.json, all.dump(2) + "\n", error)) return false;
  return true;
}

}  // namespace gb
