// The receiving side of `gblens attach` (see live.h): a listening socket in a private folder, the
// application started with the layer enabled through the loader's environment, and the wire's
// messages turned into frames, reports and counts. One frame at a time: the shared memory is the
// layer's again (ack) as soon as a frame is decoded.
#include "views/live/live.h"

#include <fcntl.h>
#include <malloc.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include "renderer/core/layout_json.h"
#include "views/capture/debris.h"
#include "views/import/import.h"
#include "views/live/live_wire.h"

extern char** environ;

namespace gb {

namespace fs = std::filesystem;

std::string layerFolder() {
  if (const char* dir = std::getenv("GBLENS_LAYER_DIR"); dir && *dir) return dir;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("layer") : (exe.parent_path() / "layer").string();
}

namespace {

// NAME=VALUE entries: the environment with `name` set to `value`, prepended to a list it holds.
void setListVariable(std::vector<std::string>& env, const std::string& name, const std::string& value) {
  for (std::string& e : env)
    if (e.rfind(name + "=", 0) == 0) {
      const std::string old = e.substr(name.size() + 1);
      e = name + "=" + value + (old.empty() ? "" : ":" + old);
      return;
    }
  env.push_back(name + "=" + value);
}

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

LiveSession::~LiveSession() {
  detach();
  for (auto& [id, m] : buffers_) munmap(const_cast<uint8_t*>(m.data), m.size);
  if (!dir_.empty()) {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  if (pid_ > 0 && status_ < 0) waitApplication(0.0);  // reaped if it is already done
}

bool LiveSession::start(const LiveOptions& o, std::string& error) {
  options_ = o;
  history_.setLimit(o.history);
  // Every frame decoded allocates its targets (tens of MB) and frees the last frame's. glibc serves
  // blocks that large with a fresh mmap each time and trims freed heap back to the system, so every
  // frame's texels landed on new pages the kernel zeroes and faults in: two thirds of the decoding
  // time (decoding builtin:gblens at 720p: 65 ms a frame, 18 ms kept on the heap), on the cores the
  // application renders with.
  // Kept on the heap, a frame reuses the pages of the one before.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // glibc's largest (a 4K rgba32f target is still mapped)
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  if (o.argv.empty()) {
    error = "APP: give the application to start (gblens attach ... -- APP ARGS...)";
    return false;
  }
  LivePlan plan;
  if (!planLive(o, plan, error)) return false;
  layout_ = plan.live;
  layoutDir_ = plan.layoutDir;
  for (const LayoutTarget& t : layout_.targets) wireNames_.push_back(t.name);
  const std::string manifest = (fs::path(o.layerDir.empty() ? layerFolder() : o.layerDir) / wire::kLayerManifest).string();
  if (!fs::exists(manifest)) {
    error = manifest + ": the gblens layer is not built (cmake --build build --target gblens_layer)";
    return false;
  }
  // In $TMPDIR (else /tmp), named by this process (pid and start time, debris.h): what a killed
  // attach left there is removed here.
  std::error_code ec;
  const std::string tmp = fs::temp_directory_path(ec).string();
  if (ec) {
    error = "TMPDIR: " + ec.message();
    return false;
  }
  for (const std::string& line : removeDebrisNamed(tmp, "gblens-attach-")) addReport(line);
  std::string tmpl = (fs::path(tmp) / ("gblens-attach-" + processStamp() + "-XXXXXX")).string();
  if (tmpl.size() + sizeof("/socket") > sizeof(sockaddr_un::sun_path)) {
    error = "TMPDIR: " + tmp + " is too long a path for a socket (at most " +
            std::to_string(sizeof(sockaddr_un::sun_path) - sizeof("/socket") - (tmpl.size() - tmp.size())) + " characters)";
    return false;
  }
  if (!mkdtemp(tmpl.data())) {
    error = "cannot make a folder for the socket in " + tmp + ": " + std::strerror(errno);
    return false;
  }
  dir_ = tmpl.c_str();
  socketPath_ = dir_ + "/socket";
  listener_ = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, socketPath_.c_str(), sizeof(addr.sun_path) - 1);
  if (listener_ < 0 || bind(listener_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 || listen(listener_, 4) != 0) {
    error = std::string("cannot listen on ") + socketPath_ + ": " + std::strerror(errno);
    return false;
  }
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.push_back(*e);
  // The loader looks for implicit layers in $XDG_DATA_DIRS/vulkan/implicit_layer.d (the XDG default
  // when unset is kept after the layer's folder).
  if (std::none_of(env.begin(), env.end(), [](const std::string& e) { return e.rfind("XDG_DATA_DIRS=", 0) == 0; }))
    env.push_back("XDG_DATA_DIRS=/usr/local/share:/usr/share");
  setListVariable(env, "XDG_DATA_DIRS", o.layerDir.empty() ? layerFolder() : o.layerDir);
  for (const std::string& name : {std::string(wire::kSocketEnv), std::string(wire::kEnableEnv), std::string("DISABLE_GBLENS_LIVE")})
    std::erase_if(env, [&](const std::string& e) { return e.rfind(name + "=", 0) == 0; });
  env.push_back(std::string(wire::kSocketEnv) + "=" + socketPath_);
  env.push_back(std::string(wire::kEnableEnv) + "=1");
  env.insert(env.end(), o.environment.begin(), o.environment.end());
  std::vector<char*> argv, envp;
  for (const std::string& a : o.argv) argv.push_back(const_cast<char*>(a.c_str()));
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  argv.push_back(nullptr);
  envp.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  if (!o.log.empty()) {
    posix_spawn_file_actions_addopen(&files, 1, o.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&files, 1, 2);
  }
  const int err = posix_spawnp(&pid_, argv[0], &files, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&files);
  if (err != 0) {
    pid_ = -1;
    error = o.argv[0] + ": cannot start it (" + std::strerror(err) + ")";
    return false;
  }
  request_ = plan.request;
  return true;
}

bool planLive(const LiveOptions& o, LivePlan& plan, std::string& error) {
  plan = LivePlan{};
  if (!o.layout.empty() || !o.layoutJson.is_null()) {
    if (o.layoutJson.is_null() ? !loadImportLayout(o.layout, layoutParameters(o.options), plan.original, plan.layoutDir, error)
                               : !parseLayout(o.layoutJson, "layout", plan.original, error))
      return false;
    plan.live = plan.original;
    if (!liveLayout(plan.live, error)) return false;
  }
  // The request is sent to each layer that connects (an application may make a second device after
  // destroying its first).
  plan.request = liveRequest(plan.original, o).dump();
  return true;
}

bool LiveSession::accept() {
  if (conn_ >= 0 || listener_ < 0 || detached_) return conn_ >= 0;
  int c = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
  if (c < 0) return false;
  std::string text;
  if (wire::receive(c, text, nullptr, 5000) != wire::Received::Message || !wire::send(c, request_)) {
    close(c);
    return false;
  }
  hello_ = nlohmann::json::parse(text, nullptr, false);
  conn_ = c;
  return true;
}

void LiveSession::addReport(const std::string& text) {
  if (said_.insert(text).second) reports_.push_back(text);
}

std::vector<std::string> LiveSession::takeReports() {
  std::vector<std::string> r;
  r.swap(reports_);
  return r;
}

// Reads what waits on the socket; true with a decoded frame.
bool LiveSession::receive(FrameSnapshot& out, LiveFrameInfo* info) {
  std::string text;
  int fd = -1;
  while (conn_ >= 0) {
    const wire::Received got = wire::receive(conn_, text, &fd, 0);
    if (got == wire::Received::Nothing) return false;
    if (got == wire::Received::Closed) {  // the application's device went away (or the application did)
      close(conn_);
      conn_ = -1;
      return false;
    }
    nlohmann::json m = nlohmann::json::parse(text, nullptr, false);
    const std::string type = m.is_object() ? m.value("type", "") : "";
    if (type == wire::kReport) addReport("layer: " + m.value("text", ""));
    if (type == wire::kPasses) suggestion_ = m;
    if (type == wire::kNoMatch) noMatch_ = true;
    const uint32_t id = m.is_object() ? m.value("id", 0u) : 0u;
    if ((type == wire::kBuffer || type == wire::kRetire) && buffers_.count(id)) {  // replaced or gone
      munmap(const_cast<uint8_t*>(buffers_[id].data), buffers_[id].size);
      buffers_.erase(id);
    }
    if (type == wire::kBuffer && fd >= 0) {
      struct stat st {};
      fstat(fd, &st);
      void* p = mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_SHARED, fd, 0);
      if (p != MAP_FAILED) buffers_[id] = {static_cast<const uint8_t*>(p), size_t(st.st_size)};
    }
    if (fd >= 0) close(fd);
    if (type != wire::kFrame) continue;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    bool ok = untouched(m) && decode(m, out, info, error) && untouched(m);
    const double decodeMs = secondsSince(start) * 1e3;
    if (!ok && error.empty()) {  // read in place while the application's GPU wrote it again
      ++counts_.overwritten;
      wire::send(conn_, nlohmann::json{{"type", wire::kAck}}.dump());
      if (options_.paced) ready();  // nobody will take this one
      continue;
    }
    wire::send(conn_, nlohmann::json{{"type", wire::kAck}}.dump());  // the layer may fill the memory again
    counts_.layer = m.value("stats", nlohmann::json::object());
    counts_.dropped = counts_.layer.value("dropped", uint64_t(0));
    counts_.notAsked = counts_.layer.value("not_asked", uint64_t(0));
    counts_.appFrames = counts_.layer.value("frames", uint64_t(0));
    if (!ok) {
      ++counts_.undecodable;
      addReport(error);
      if (options_.paced) ready();
      continue;
    }
    const double ready = double(m.value("ready_ns", uint64_t(0)) - m.value("end_ns", uint64_t(0))) * 1e-6;
    counts_.meanReadyMs = (counts_.meanReadyMs * double(counts_.received) + ready) / double(counts_.received + 1);
    const double latency = double(wire::monotonicNs() - m.value("end_ns", uint64_t(0))) * 1e-6;
    counts_.meanLatencyMs = (counts_.meanLatencyMs * double(counts_.received) + latency) / double(counts_.received + 1);
    counts_.maxLatencyMs = std::max(counts_.maxLatencyMs, latency);
    counts_.meanDecodeMs = (counts_.meanDecodeMs * double(counts_.received) + decodeMs) / double(counts_.received + 1);
    ++counts_.received;
    if (info) info->latencyMs = latency, info->endNs = m.value("end_ns", uint64_t(0));
    history_.push(out, m.value("app_frame", uint64_t(0)), m.value("stream", uint64_t(0)), m.value("end_ns", uint64_t(0)));
    boundBuffers_.swap(decodedBound_);  // the bytes of the frame returned, not of one dropped while read
    return true;
  }
  return false;
}

void LiveSession::ready(unsigned frames) {
  if (conn_ >= 0 && options_.paced) wire::send(conn_, nlohmann::json{{"type", wire::kReady}, {"frames", frames}}.dump());
}

bool LiveSession::poll(FrameSnapshot& out, LiveFrameInfo* info) {
  accept();
  return receive(out, info);
}

bool LiveSession::wait(FrameSnapshot& out, double seconds, LiveFrameInfo* info, int wakeFd) {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    if (poll(out, info)) return true;
    const bool alive = running();
    if ((!alive && conn_ < 0) || secondsSince(start) >= seconds) return false;
    pollfd p[2] = {{conn_ >= 0 ? conn_ : listener_, POLLIN, 0}, {wakeFd, POLLIN, 0}};
    ::poll(p, wakeFd >= 0 ? 2 : 1, alive ? 10 : 0);
    if (wakeFd >= 0 && (p[1].revents & POLLIN)) return false;
    if (!alive && conn_ >= 0 && !(p[0].revents & POLLIN)) {  // the application is gone and said all it had
      close(conn_);
      conn_ = -1;
    }
  }
}

bool LiveSession::running() {
  if (pid_ <= 0 || status_ >= 0) return false;
  int s = 0;
  rusage usage{};
  if (wait4(pid_, &s, WNOHANG, &usage) != pid_) return true;
  peakKb_ = usage.ru_maxrss;
  status_ = WIFEXITED(s) ? WEXITSTATUS(s) : 128 + WTERMSIG(s);
  return false;
}

void LiveSession::detach() {
  if (detached_) return;
  detached_ = true;
  if (conn_ >= 0) {
    wire::send(conn_, nlohmann::json{{"type", wire::kDetach}}.dump());
    close(conn_);
    conn_ = -1;
  }
  if (listener_ >= 0) close(listener_), listener_ = -1;
}

void LiveSession::stop() {
  detach();
  if (!running()) return;
  kill(pid_, SIGTERM);
  if (waitApplication(3.0) < 0) {
    kill(pid_, SIGKILL);
    waitApplication();
  }
}

int LiveSession::waitApplication(double seconds) {
  const auto start = std::chrono::steady_clock::now();
  while (running()) {
    if (seconds >= 0.0 && secondsSince(start) >= seconds) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return status_;
}

}  // namespace gb
