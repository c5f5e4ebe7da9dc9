// One pair's report folder: index.html (the page, static), report.js (what it shows), report.json (the
// same report as `compare --json`, file names relative to the folder), img/ (FLIP maps, the
// mask) and data/ (per group: the texels the views, the values in texels and the hover readout read).
#include <filesystem>
#include <utility>

#include "renderer/core/assert.h"
#include "views/analysis/flip.h"
#include "views/capture/image_io.h"
#include "views/report/report.h"
#include "views/report/report_internal.h"

namespace gb {

namespace fs = std::filesystem;

bool writePage(const std::string& dir, const nlohmann::json& data, std::string& error) {
  std::string html = reportPageHtml();
  // index.js after page.js: its indexPage is the one the page calls (the later definition wins).
  for (auto [slot, text] : {std::pair<std::string, const char*>{"/*gblens:texels.js*/", reportTexelsJs()},
                            {"/*gblens:page.js*/", reportPageJs()}, {"/*gblens:index.js*/", reportIndexJs()}}) {
    const size_t at = html.find(slot);
    GB_ASSERT(at != std::string::npos);
    html.replace(at, slot.size(), text);
  }
  // The data as a script: a page opened from disk may load scripts beside it, not read files.
  return writeTextAtomically((fs::path(dir) / "report.js").string(), "gblensReport(" + data.dump() + ");\n", error) &&
         writeTextAtomically((fs::path(dir) / "index.html").string(), html, error);
}

bool writeReportContents(const Capture& a, const Capture& b, const CompareReport& report, const std::string& dir,
                         std::string& error) {
  std::error_code ec;
  for (const char* sub : {"img", "data"})
    if (fs::create_directories(fs::path(dir) / sub, ec); ec) {
      error = dir + "/" + sub + ": cannot create (" + ec.message() + ")";
      return false;
    }
  nlohmann::json j = report.json();
  auto png = [&](const std::string& name, const Rgba8Image& img, nlohmann::json& field) {
    if (name.empty()) error = "a group key cannot be a file name (use a-z, A-Z, 0-9, _, . and -)";
    if (name.empty() || img.pixels.empty() || !writePng((fs::path(dir) / "img" / name).string(), img, error)) return false;
    field = "img/" + name;
    return true;
  };
  nlohmann::json groups = nlohmann::json::object();
  for (size_t i = 0; i < report.groups.size(); ++i) {
    const GroupResult& g = report.groups[i];
    const std::string file = compareFileName(g.group.key, "");
    if (file.empty()) {
      error = "a group key cannot be a file name (use a-z, A-Z, 0-9, _, . and -)";
      return false;
    }
    // No heat map image: the page draws |A-B| from the error in the data, scaled to the group's
    // largest, with its legend (`compare -o DIR` writes the heat map images).
    nlohmann::json meta;
    if (!writeGroupData(a, b, g, (fs::path(dir) / "data" / file).string(), meta, error)) return false;
    meta["stem"] = "data/" + file;
    groups[g.group.key] = meta;
  }
  for (size_t i = 0; i < report.flips.size(); ++i) {
    const FlipResult& f = report.flips[i];
    // The map alone, as palette indices (a fraction of the RGBA image's size); the page draws the
    // legend from the palette (`compare -o DIR` writes the map with its legend).
    const std::string name = "flip_" + f.target + ".png";
    std::vector<uint8_t> indices(f.errors.size());
    for (size_t k = 0; k < indices.size(); ++k) indices[k] = magmaIndex(f.errors[k]);
    if (!writeIndexedPng((fs::path(dir) / "img" / name).string(), f.width, f.height, indices, magmaPalette(), error))
      return false;
    j["flip"][i]["heatmap"] = "img/" + name;
    for (const GroupResult& g : report.groups)  // the FLIP map is shown with the target's group
      if (g.target == f.target && groups.contains(g.group.key)) groups[g.group.key]["flip"] = j["flip"][i]["heatmap"];
  }
  if (!report.mask.empty() && !png("mask.png", maskImage(report.mask), j["mask"]["image"])) return false;
  return writeTextAtomically((fs::path(dir) / "report.json").string(), j.dump(2) + "\n", error) &&
         writePage(dir, {{"kind", "pair"}, {"report", j}, {"groups", groups}, {"magma", magmaPalette()}}, error);
}

bool writeReport(const Capture& a, const Capture& b, const CompareReport& report, const std::string& dir,
                 std::string& error) {
  return replaceDirectory(dir, "report.js", "compare report", [&](const std::string& tmp, std::string& e) {
    return writeReportContents(a, b, report, tmp, e);
  }, error);
}

}  // namespace gb
