// Bench plots through gnuplot (pngcairo): time_vs_error.png (a panel per quality group and
// scene: one point per variant with min-max bars, the Pareto frontier as a line, the defaults
// circled), time_vs_lights.png (log-log time vs lights and vs pixels, a line per scene and
// method), depth_range.png (position error vs far/near per depth source) and methods_vs_lights.png
// (the method comparison: log-log time vs lights and culling efficiency per method). The data and the
// script are kept in plot/ next to the images so a plot can be restyled by hand.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "app/bench/bench_report.h"
#include "views/capture/image_io.h"

namespace gb {

static std::string fileSafe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  return s;
}

static std::string gpQuote(const std::string& s) {  // a gnuplot string literal
  std::string q = "\"";
  for (char c : s) q += c == '"' ? '\'' : c;
  return q + "\"";
}

static std::string shortScene(const std::string& scene) {
  if (scene.rfind("builtin:", 0) == 0) return scene.substr(8);
  return std::filesystem::path(scene).stem().string();
}

static bool writeText(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  return bool(f);
}

// Runs gnuplot on `script`, which writes `tmpImage`; renames it to `image` on success.
static bool runGnuplot(const std::string& script, const std::string& tmpImage, const std::string& image,
                       std::string& error) {
  std::string cmd = "gnuplot " + gpQuote(script) + " 2>&1";
  std::string output;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof buf, p)) output += buf;
    int status = pclose(p);
    if (status != 0) {
      error = "gnuplot failed on " + script + (output.empty() ? "" : ": " + output.substr(0, 400));
      std::filesystem::remove(tmpImage);
      return false;
    }
  } else {
    error = "cannot run gnuplot (install gnuplot-nox)";
    return false;
  }
  std::error_code ec;
  std::filesystem::rename(tmpImage, image, ec);
  if (ec) error = image + ": " + ec.message();
  return !ec;
}

static const char* kHeader =
    "set terminal pngcairo size %d,%d font 'DejaVu Sans,10' noenhanced\nset output %s\nset grid lc rgb '#dddddd'\n";

static std::string header(int w, int h, const std::string& out) {
  char buf[512];
  std::snprintf(buf, sizeof buf, kHeader, w, h, gpQuote(out).c_str());
  return buf;
}

// Point labels cycling through four positions (above right, below right, above left, below
// left), so clustered neighbours do not print over each other.
static std::string labels(const std::string& file) {
  const char* placements[4] = {"offset 0.8,0.7 left", "offset 0.8,-0.8 left", "offset -0.8,0.7 right",
                               "offset -0.8,-0.8 right"};
  std::string out;
  for (int k = 0; k < 4; ++k)
    out += std::string(k ? ", \\\n  " : "") + gpQuote(file) + " every 4::" + std::to_string(k) + " using 1:2:5 with labels " +
           placements[k] + " font ',8' tc rgb '#222222'";
  return out;
}

static bool plotTimeVsError(const BenchReport& r, const std::string& dir, std::string& error) {
  namespace fs = std::filesystem;
  std::vector<std::string> scenes;
  for (const BenchRow& row : r.rows)
    if (row.measured && std::find(scenes.begin(), scenes.end(), row.scene) == scenes.end()) scenes.push_back(row.scene);
  std::vector<const BenchGroup*> groups;
  for (const BenchGroup& g : benchGroups())
    if (!g.metric.empty()) groups.push_back(&g);
  if (scenes.empty()) return true;
  const std::string plotDir = (fs::path(dir) / "plot").string();
  std::ostringstream gp;
  const std::string tmp = (fs::path(dir) / ".time_vs_error.tmp.png").string();
  gp << header(int(std::max<size_t>(2, scenes.size()) * 640), int(430 * groups.size()), tmp);
  gp << "set multiplot layout " << groups.size() << "," << scenes.size()
     << " title \"gblens bench: frame time vs error, one point per variant\\n(bars: min-max of the timed frames; red "
        "line: Pareto frontier; circle: the defaults)\" font ',12'\n";
  gp << "set key off\nset logscale x\nset format x '%.0e'\nset ylabel 'frame ms (median)'\nset offsets graph 0.08, "
        "graph 0.25, graph 0.12, graph 0.12\n";
  for (const BenchGroup* g : groups)
    for (const std::string& scene : scenes) {
      std::string base = fileSafe(shortScene(scene) + "_" + g->name);
      std::ostringstream pts, front, def;
      std::vector<std::pair<double, double>> frontier;
      std::vector<const BenchRow*> shown;
      for (const BenchRow& row : r.rows)
        if (row.scene == scene && row.measured && (row.group == g->name || row.group == "default") &&
            row.error.count(g->metric))
          shown.push_back(&row);
      // Sorted by error then time, so neighbours on the plot are neighbours in the file and
      // their labels alternate above and below (every 2 / every 2::1 below).
      std::sort(shown.begin(), shown.end(), [&](const BenchRow* a, const BenchRow* b) {
        double ea = a->error.at(g->metric), eb = b->error.at(g->metric);
        return ea != eb ? ea < eb : a->frameMs.median < b->frameMs.median;
      });
      for (const BenchRow* row : shown) {
        double x = std::max(row->error.at(g->metric), 1e-12);  // log axis: exact zeros drawn at 1e-12
        pts << x << " " << row->frameMs.median << " " << row->frameMs.min << " " << row->frameMs.max << " "
            << gpQuote(row->label) << "\n";
        if (row->group == "default") def << x << " " << row->frameMs.median << "\n";
        if (row->frontier) frontier.push_back({x, row->frameMs.median});
      }
      std::sort(frontier.begin(), frontier.end());
      for (auto& [x, y] : frontier) front << x << " " << y << "\n";
      writeText(plotDir + "/" + base + ".dat", pts.str());
      writeText(plotDir + "/" + base + "_frontier.dat", front.str());
      writeText(plotDir + "/" + base + "_default.dat", def.str());
      gp << "set title " << gpQuote(shortScene(scene) + ": " + g->title) << "\n";
      gp << "set xlabel " << gpQuote(g->metric + " (log)") << "\n";
      if (pts.str().empty()) {
        gp << "set label 1 'no data' at graph 0.5, graph 0.5 center\nplot [1e-9:1] [0:1] 1/0\nunset label 1\n";
        continue;
      }
      gp << "plot " << gpQuote(plotDir + "/" + base + ".dat")
         << " using 1:2:3:4 with yerrorbars pt 7 ps 0.9 lc rgb '#4477aa', \\\n  "
         << gpQuote(plotDir + "/" + base + "_frontier.dat") << " using 1:2 with linespoints lw 2 pt 7 ps 0.9 lc rgb '#cc3311', \\\n  "
         << gpQuote(plotDir + "/" + base + "_default.dat") << " using 1:2 with points pt 6 ps 3 lw 2 lc rgb '#000000', \\\n  "
         << labels(plotDir + "/" + base + ".dat") << "\n";
    }
  gp << "unset multiplot\n";
  std::string script = plotDir + "/time_vs_error.gp";
  writeText(script, gp.str());
  return runGnuplot(script, tmp, (fs::path(dir) / "time_vs_error.png").string(), error);
}

static bool plotWorkloads(const BenchReport& r, const std::string& dir, std::string& error) {
  namespace fs = std::filesystem;
  const std::string plotDir = (fs::path(dir) / "plot").string();
  // One series per scene and method: Performance adds methods by adding rows.
  std::map<std::string, std::vector<std::pair<double, double>>> lights, pixels;
  for (const BenchRow& row : r.rows) {
    if (!row.measured) continue;
    std::string series = shortScene(row.scene) + " " + name(row.options.method);
    if (row.group == "lights" || row.group == "default")
      lights[series].push_back({std::max(row.options.lights, 1), row.frameMs.median});
    if (row.group == "size" || row.group == "default")
      pixels[series].push_back({double(row.options.width) * row.options.height / 1e6, row.frameMs.median});
  }
  if (lights.empty() && pixels.empty()) return true;
  const std::string tmp = (fs::path(dir) / ".time_vs_lights.tmp.png").string();
  std::ostringstream gp;
  gp << header(1400, 520, tmp);
  gp << "set multiplot layout 1,2 title 'gblens bench: frame time vs workload (log-log)' font ',12'\n";
  gp << "set logscale xy\nset key top left\nset ylabel 'frame ms (median)'\n";
  auto panel = [&](const char* title, const char* xlabel, const std::string& tag,
                   std::map<std::string, std::vector<std::pair<double, double>>>& data) {
    gp << "set title " << gpQuote(title) << "\nset xlabel " << gpQuote(xlabel) << "\n";
    std::string plot = "plot ";
    int k = 0;
    for (auto& [series, pts] : data) {
      std::sort(pts.begin(), pts.end());
      pts.erase(std::unique(pts.begin(), pts.end(), [](auto& a, auto& b) { return a.first == b.first; }), pts.end());
      std::ostringstream d;
      for (auto& [x, y] : pts) d << x << " " << y << "\n";
      std::string file = plotDir + "/" + tag + "_" + fileSafe(series) + ".dat";
      writeText(file, d.str());
      plot += std::string(k++ ? ", " : "") + gpQuote(file) + " using 1:2 with linespoints lw 2 pt 7 title " + gpQuote(series);
    }
    gp << (k ? plot : "plot [1:10] [1:10] 1/0 notitle") << "\n";
  };
  panel("time vs point lights (0 lights drawn at 1)", "point lights", "lights", lights);
  panel("time vs output size", "megapixels", "pixels", pixels);
  gp << "unset multiplot\n";
  std::string script = plotDir + "/time_vs_lights.gp";
  writeText(script, gp.str());
  return runGnuplot(script, tmp, (fs::path(dir) / "time_vs_lights.png").string(), error);
}

static bool plotDepthRange(const BenchReport& r, const std::string& dir, std::string& error) {
  namespace fs = std::filesystem;
  if (r.depthRange.empty()) return true;
  const std::string plotDir = (fs::path(dir) / "plot").string();
  std::map<std::string, std::ostringstream> series;
  for (const DepthRangeRow& d : r.depthRange) {
    std::ostringstream& s = series[d.source];
    s.precision(9);
    s << d.ratio << " " << std::max(d.relMax, 1e-12) << "\n";
  }
  const std::string tmp = (fs::path(dir) / ".depth_range.tmp.png").string();
  std::ostringstream gp;
  gp << header(900, 560, tmp);
  gp << "set title 'builtin:depth-range: position reconstruction error vs far/near' font ',12'\n";
  gp << "set logscale xy\nset format y '%.0e'\nset key outside right\nset xlabel 'far / near'\n"
        "set ylabel 'max |P - P_ref| / depth'\nset label 1 'd24_standard lies on d32_standard: near depth 1 a float32 "
        "has 24 bits too' at graph 0.02, graph 0.96 font ',9'\n";
  std::string plot = "plot 1e-6 with lines dt 2 lc rgb '#666666' title 'target 1e-6', 2e-6 with lines dt 3 lc rgb '#999999' title '2e-6'";
  for (auto& [source, data] : series) {
    std::string file = plotDir + "/depth_range_" + fileSafe(source) + ".dat";
    writeText(file, data.str());
    plot += ", " + gpQuote(file) + " using 1:2 with linespoints lw 2 pt 7 title " + gpQuote(source);
  }
  gp << plot << "\n";
  std::string script = plotDir + "/depth_range.gp";
  writeText(script, gp.str());
  return runGnuplot(script, tmp, (fs::path(dir) / "depth_range.png").string(), error);
}

// methods_vs_lights.png: the method comparison, log-log frame time vs point lights, a line per
// method and size; beside it the culling efficiency (work / ideal pairs) vs lights.
static bool plotMethods(const BenchReport& r, const std::string& dir, std::string& error) {
  namespace fs = std::filesystem;
  if (r.methods.empty()) return true;
  const std::string plotDir = (fs::path(dir) / "plot").string();
  std::map<std::string, std::vector<std::pair<double, double>>> time, work;
  std::vector<std::string> order;  // series in table order
  for (const auto& [method, flags] : benchMethods())
    for (const MethodRow& m : r.methods) {
      if (m.method != method || !m.measured) continue;
      std::string series = method + " " + std::to_string(m.options.width) + "x" + std::to_string(m.options.height);
      if (std::find(order.begin(), order.end(), series) == order.end()) order.push_back(series);
      double x = std::max(m.options.lights, 1);
      time[series].push_back({x, m.frameMs.median});
      if (m.cullingValid && m.workOverIdeal > 0) work[series].push_back({x, m.workOverIdeal});
    }
  // A colour per method, a dash pattern per size: the same in both panels.
  std::vector<std::string> sizes;
  for (const std::string& series : order) {
    std::string size = series.substr(series.find(' ') + 1);
    if (std::find(sizes.begin(), sizes.end(), size) == sizes.end()) sizes.push_back(size);
  }
  auto style = [&](const std::string& series) {
    static const char* colours[] = {"#4477aa", "#ee6677", "#228833", "#ccbb44", "#66ccee", "#aa3377"};
    std::string method = series.substr(0, series.find(' '));
    size_t c = 0;
    for (; c < benchMethods().size() && benchMethods()[c].first != method; ++c) {}
    size_t d = std::find(sizes.begin(), sizes.end(), series.substr(series.find(' ') + 1)) - sizes.begin();
    return std::string("lc rgb '") + colours[c % 6] + "' dt " + std::to_string(d + 1);
  };
  const std::string tmp = (fs::path(dir) / ".methods_vs_lights.tmp.png").string();
  std::ostringstream gp;
  gp << header(1400, 560, tmp);
  gp << "set multiplot layout 1,2 title " << gpQuote("gblens bench: lighting methods on " + r.methods.front().scene +
                                                       " (" + r.meta.value("device", std::string("?")) + ")")
     << " font ',12'\n";
  gp << "set logscale xy\nset key top left\nset xlabel 'point lights (log; 0 drawn at 1)'\n";
  auto panel = [&](const char* title, const char* ylabel, const std::string& tag,
                   std::map<std::string, std::vector<std::pair<double, double>>>& data, const std::string& extra) {
    gp << "set title " << gpQuote(title) << "\nset ylabel " << gpQuote(ylabel) << "\n";
    std::string plot = "plot " + extra;
    int k = extra.empty() ? 0 : 1;
    for (const std::string& series : order) {
      auto it = data.find(series);
      if (it == data.end() || it->second.empty()) continue;
      std::sort(it->second.begin(), it->second.end());
      std::ostringstream d;
      for (auto& [x, y] : it->second) d << x << " " << y << "\n";
      std::string file = plotDir + "/methods_" + tag + "_" + fileSafe(series) + ".dat";
      writeText(file, d.str());
      plot += std::string(k++ ? ", " : "") + gpQuote(file) + " using 1:2 with linespoints lw 2 pt 7 " + style(series) +
              " title " + gpQuote(series);
    }
    gp << (k ? plot : "plot [1:10] [1:10] 1/0 notitle") << "\n";
  };
  panel("frame time vs point lights (log-log; median of interleaved rounds)", "frame ms (median)", "time", time, "");
  gp << "set key top right\n";  // forward's line runs along the top left
  panel("culling efficiency: fragment invocations / ideal pixel-light pairs", "work / ideal (1 = no wasted work)",
        "work", work, "1 with lines dt 2 lc rgb '#666666' title 'ideal', 1.5 with lines dt 3 lc rgb '#999999' title 'target 1.5'");
  gp << "unset multiplot\n";
  std::string script = plotDir + "/methods_vs_lights.gp";
  writeText(script, gp.str());
  return runGnuplot(script, tmp, (fs::path(dir) / "methods_vs_lights.png").string(), error);
}

bool writeBenchPlots(const BenchReport& r, const std::string& dir, std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(dir) / "plot", ec);
  if (ec) {
    error = dir + "/plot: " + ec.message();
    return false;
  }
  return plotTimeVsError(r, dir, error) && plotWorkloads(r, dir, error) && plotDepthRange(r, dir, error) &&
         plotMethods(r, dir, error);
}

}  // namespace gb
