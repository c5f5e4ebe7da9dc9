// GUI test helpers: processes, Xvfb, event-log polling, screenshots.
#include "tests/support/test_paths.h"
#include "tests/gui/gui_util.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

namespace gb::gui {

bool haveTool(const std::string& name) {
  int status = 0;
  run("command -v " + name + " >/dev/null 2>&1", &status);
  return status == 0;
}

std::string run(const std::string& command, int* status) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (!p) {
    if (status) *status = -1;
    return out;
  }
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  int st = pclose(p);
  if (status) *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}

pid_t spawn(const std::vector<std::string>& argv, const std::vector<std::string>& env, const std::string& logFile) {
  pid_t pid = fork();
  if (pid != 0) return pid;
  // Child: its own process group (so a stuck child's children can be found), output to the log.
  setpgid(0, 0);
  int fd = open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
  }
  for (const std::string& e : env) putenv(strdup(e.c_str()));
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  execvp(args[0], args.data());
  _exit(127);
}

bool waitExit(pid_t pid, double seconds, int& status) {
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (true) {
    int st = 0;
    pid_t r = waitpid(pid, &st, WNOHANG);
    if (r == pid) {
      status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      return true;
    }
    if (r < 0 || std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void terminate(pid_t pid) {
  if (pid <= 0) return;
  int status;
  kill(pid, SIGTERM);
  if (waitExit(pid, 3.0, status)) return;
  kill(pid, SIGKILL);
  waitExit(pid, 3.0, status);
}

bool Xvfb::start(int width, int height, std::string& error) {
  int fds[2];
  if (pipe(fds) != 0) {
    error = "pipe failed";
    return false;
  }
  pid = fork();
  if (pid == 0) {
    close(fds[0]);
    int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, 1);
    dup2(devnull, 2);
    std::string fd = std::to_string(fds[1]), screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", screen.c_str(), "-nolisten", "tcp", "-noreset",
           static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  // Xvfb writes the display number it chose once it accepts connections.
  std::string number;
  char c;
  auto end = std::chrono::steady_clock::now() + std::chrono::seconds(15);
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  while (std::chrono::steady_clock::now() < end) {
    ssize_t n = read(fds[0], &c, 1);
    if (n == 1 && c == '\n') break;
    if (n == 1) {
      number += c;
      continue;
    }
    if (n == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  close(fds[0]);
  if (number.empty()) {
    error = "Xvfb did not report a display";
    stop();
    return false;
  }
  display = ":" + number;
  return true;
}

void Xvfb::stop() {
  terminate(pid);
  pid = -1;
}

nlohmann::json waitForLine(const std::string& file, double seconds, const std::function<bool(const nlohmann::json&)>& pred,
                           size_t& cursor) {
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    std::ifstream in(file);
    std::string line;
    for (size_t index = 0; std::getline(in, line); ++index) {
      if (index < cursor || line.empty() || line.back() != '}') continue;  // the writer may be mid-line
      nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (!j.is_discarded() && pred(j)) {
        cursor = index + 1;
        return j;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return nullptr;
}

bool screenshot(const std::string& display, const std::string& png, Screenshot& out, std::string& error) {
  int status = 0;
  std::string xwd = png + ".xwd";
  run("xwd -root -silent -display " + display + " > '" + xwd + "' && convert 'xwd:" + xwd + "' '" + png + "'", &status);
  std::remove(xwd.c_str());
  if (status != 0) {
    error = "xwd/convert failed for " + png;
    return false;
  }
  auto in = OIIO::ImageInput::open(png);
  if (!in) {
    error = "cannot read " + png;
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  out.width = spec.width;
  out.height = spec.height;
  std::vector<float> all(size_t(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data());
  out.rgb.resize(size_t(spec.width) * spec.height * 3);
  for (size_t i = 0; i < size_t(spec.width) * spec.height; ++i)
    for (int c = 0; c < 3; ++c) out.rgb[i * 3 + c] = all[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
  return true;
}

std::vector<float> thumbnail(const Screenshot& s, int x0, int y0, int x1, int y1, int n) {
  std::vector<float> t(size_t(n) * n * 3, 0.0f);
  std::vector<int> count(size_t(n) * n, 0);
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, s.width);
  y1 = std::min(y1, s.height);
  if (x1 <= x0 || y1 <= y0) return t;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      int bx = (x - x0) * n / (x1 - x0), by = (y - y0) * n / (y1 - y0);
      size_t b = size_t(by) * n + bx;
      for (int c = 0; c < 3; ++c) t[b * 3 + c] += s.at(x, y)[c];
      count[b]++;
    }
  for (size_t b = 0; b < count.size(); ++b)
    for (int c = 0; c < 3; ++c) t[b * 3 + c] /= std::max(count[b], 1);
  return t;
}

double meanAbsDifference(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) d += std::abs(a[i] - b[i]);
  return a.empty() ? 0.0 : d / double(a.size());
}

double standardDeviation(const std::vector<float>& v) {
  double mean = 0, sq = 0;
  for (float x : v) mean += x;
  mean /= std::max<size_t>(v.size(), 1);
  for (float x : v) sq += (x - mean) * (x - mean);
  return std::sqrt(sq / std::max<size_t>(v.size(), 1));
}

bool Session::openDisplay(const std::filesystem::path& dir, int width, int height, std::string& error) {
  dir_ = dir;
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
  std::filesystem::create_directories(dir_, ec);
  if (ec) {
    error = dir_.string() + ": " + ec.message();
    return false;
  }
  return xvfb_.start(width, height, error);
}

bool Session::openTestDisplay(const std::string& prefix, int width, int height, std::string& error) {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  return openDisplay(std::filesystem::path(GBLENS_BUILD_DIR) / (prefix + test), width, height, error);
}

std::string missingTool() {
  for (const char* tool : {"xdotool", "xwd", "convert"})
    if (!haveTool(tool)) return tool;
  return "";
}

void Session::closeDisplay() {
  terminate(viewer_);
  viewer_ = -1;
  xvfb_.stop();
}

std::string Session::xdotool(const std::string& args) const {
  return run("DISPLAY=" + xvfb_.display + " xdotool " + args + " 2>&1");
}

nlohmann::json Session::waitEvent(const std::function<bool(const nlohmann::json&)>& pred, double seconds) {
  return waitForLine((dir_ / "events.jsonl").string(), seconds, pred, eventCursor_);
}

}  // namespace gb::gui
