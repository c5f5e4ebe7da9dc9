// RenderDoc replay in a child process (see renderdoc_replay.h): the embedded script is written to a
// private temporary folder, run by /usr/bin/python3 with a time limit (replay_child.h: its own
// process group, killed with gblens), and the folder removed.
#include "views/import/renderdoc_replay.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "renderer/core/json_read.h"
#include "views/import/replay_child.h"

namespace gb {

const char* renderDocReplayScript();  // generated from renderdoc_replay.py (cmake/EmbedText.cmake)

namespace {

namespace fs = std::filesystem;

// The private folder for the script, its output and texel files (replay_child.h).
using TempFolder = ReplayFolder;

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

bool readBytes(const fs::path& p, std::vector<uint8_t>& out) {
  std::ifstream f(p, std::ios::binary);
  if (!f) return false;
  out.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  return true;
}

// The script's stderr: progress lines ("progress: ...") and, on failure, its one-line message. RenderDoc
// prints lines of its own there too (e.g. "More debugging information may be available by enabling
// API validation on replay", after the script's message): the script's messages name the capture,
// so the last line that does is preferred.
struct ScriptLog {
  std::string lastProgress, lastMessage;
  ScriptLog(const std::string& text, const std::string& rdc) {
    std::stringstream s(text);
    std::string line, lastOther;
    while (std::getline(s, line)) {
      if (line.empty()) continue;
      if (line.rfind("progress: ", 0) == 0)
        lastProgress = line.substr(10);
      else if (line.rfind(rdc + ":", 0) == 0 || line.rfind("usage:", 0) == 0)
        lastMessage = line;
      else
        lastOther = line;
    }
    if (lastMessage.empty()) lastMessage = lastOther;
  }
};

// The limits: the environment's, the caller's, or the defaults (the overall one grows with the
// capture's size: a large capture takes longer to load).
ChildLimits replayLimits(const RdcReplayOptions& o, const std::string& rdc) {
  ChildLimits l;
  l.stallSeconds = o.stallSeconds > 0 ? o.stallSeconds : kReplayStallSeconds;
  std::error_code ec;
  const uintmax_t bytes = fs::file_size(rdc, ec);
  l.busySeconds = o.busySeconds > 0 ? o.busySeconds
                                    : kReplayBusySeconds + int(std::min<uintmax_t>(ec ? 0 : bytes >> 20, 10 * 6000) / 10);
  l.limitSeconds = o.limitSeconds > 0 ? o.limitSeconds
                                      : kReplayLimitSeconds + int(std::min<uintmax_t>(ec ? 0 : bytes >> 20, 10 * 6000) / 10);
  if (const char* v = std::getenv("GBLENS_RENDERDOC_STALL"); v && std::atoi(v) > 0) l.stallSeconds = std::atoi(v);
  if (const char* v = std::getenv("GBLENS_RENDERDOC_BUSY"); v && std::atoi(v) > 0) l.busySeconds = std::atoi(v);
  if (const char* v = std::getenv("GBLENS_RENDERDOC_TIMEOUT"); v && std::atoi(v) > 0) l.limitSeconds = std::atoi(v);
  return l;
}

// Runs the script with `args` once; true with its JSON result, else false with one line in `error`
// (`crashed`: it ended by a signal).
bool runScriptOnce(const std::string& rdc, const std::vector<std::string>& args, TempFolder& tmp,
                   const RdcReplayOptions& o, nlohmann::json& result, std::string& error, bool& crashed);

// Runs the script with `args`; a replay that crashes is started once more (RenderDoc 1.24 on
// lavapipe crashes now and then opening a capture it opens every other time: the commands are
// reads, so a second run is the same run). True with its JSON result, else one line in `error`.
bool runScript(const std::string& rdc, const std::vector<std::string>& args, TempFolder& tmp,
               const RdcReplayOptions& o, nlohmann::json& result, std::string& error) {
  bool crashed = false;
  if (runScriptOnce(rdc, args, tmp, o, result, error, crashed)) return true;
  if (!crashed) return false;
  error.clear();
  return runScriptOnce(rdc, args, tmp, o, result, error, crashed);
}

bool runScriptOnce(const std::string& rdc, const std::vector<std::string>& args, TempFolder& tmp,
                   const RdcReplayOptions& o, nlohmann::json& result, std::string& error, bool& crashed) {
  crashed = false;
  if (tmp.path.empty()) {
    error = "cannot create a temporary folder in " + fs::temp_directory_path().string();
    return false;
  }
  if (access(o.python.c_str(), X_OK) != 0) {
    error = o.python + " not found: reading RenderDoc captures needs Python 3 and python3-renderdoc";
    return false;
  }
  const fs::path script = tmp.path / "renderdoc_replay.py", out = tmp.path / "stdout", err = tmp.path / "stderr";
  if (!(std::ofstream(script, std::ios::binary) << renderDocReplayScript())) {
    error = "cannot write " + script.string();
    return false;
  }

  std::vector<std::string> argv = {o.python, script.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  const ChildLimits limits = replayLimits(o, rdc);
  ChildOutcome child;
  if (!runBoundedChild(argv, out, err, limits, tmp, child, error)) {
    error = rdc + ": " + error;
    return false;
  }
  const int status = child.status;

  const ScriptLog log(readText(err), rdc);
  const std::string doing = log.lastProgress.empty() ? "" : " (while " + log.lastProgress + ")";
  if (child.stalled) {
    error = rdc + ": RenderDoc's replay made no progress for " +
            std::to_string(child.busy ? limits.busySeconds : limits.stallSeconds) + " s" + doing +
            (child.busy ? " (busy, without a word): ended (GBLENS_RENDERDOC_BUSY=SECONDS allows longer)"
                        : " (idle): ended (GBLENS_RENDERDOC_STALL=SECONDS allows longer)");
    return false;
  }
  if (child.timedOut) {
    error = rdc + ": RenderDoc's replay did not finish within " + std::to_string(limits.limitSeconds) + " s" + doing +
            ": ended (GBLENS_RENDERDOC_TIMEOUT=SECONDS allows longer)";
    return false;
  }
  if (WIFSIGNALED(status)) {
    crashed = true;
    error = rdc + ": RenderDoc's replay crashed (signal " + std::to_string(WTERMSIG(status)) + ", twice)" + doing +
            "; the capture may not replay on this machine's driver";
    return false;
  }
  const int exitCode = WEXITSTATUS(status);
  if (exitCode != 0) {
    if (log.lastMessage.find("No module named 'renderdoc'") != std::string::npos)
      error = "the Python module renderdoc is not installed for " + o.python + " (apt-get install python3-renderdoc)";
    else if (exitCode == 2 && log.lastMessage.rfind(rdc + ":", 0) == 0)
      error = log.lastMessage;
    else if (exitCode == 2 && !log.lastMessage.empty())
      error = rdc + ": " + log.lastMessage + doing;
    else
      error = rdc + ": RenderDoc's replay failed" + doing + ": " + (log.lastMessage.empty() ? "no message" : log.lastMessage);
    return false;
  }
  // The result is the last line of stdout (RenderDoc may print before it).
  std::string text = readText(out);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  size_t start = text.rfind('\n');
  std::string why;
  if (!parseJson(text.substr(start == std::string::npos ? 0 : start + 1), "result", result, why) || !result.is_object()) {
    error = rdc + ": RenderDoc's replay printed no result" + doing;
    return false;
  }
  return true;
}

// A result of another shape than the script writes: named, not a crash.
bool unexpectedResult(const std::string& rdc, const std::exception& e, std::string& error) {
  error = rdc + ": RenderDoc's replay printed an unexpected result (" + e.what() + ")";
  return false;
}

RdcTexture textureFromJson(const nlohmann::json& j) {
  RdcTexture t;
  t.name = j.value("name", "");
  t.id = j.value("id", uint64_t(0));
  t.autoName = j.value("auto", false);
  const nlohmann::json& f = j.at("format");
  RdcFormat format{f.value("name", ""), f.value("type", ""), f.value("compType", ""), f.value("compCount", 0u),
                   f.value("compByteWidth", 0u), f.value("bgra", false)};
  t.format = format.name;
  t.texelFormat = texelFormatOf(format);
  t.width = j.value("width", 0u);
  t.height = j.value("height", 0u);
  t.depth = j.value("depth", 1u);
  t.mips = j.value("mips", 1u);
  t.layers = j.value("arraysize", 1u);
  t.samples = j.value("samples", 1u);
  t.reads = j.value("reads", std::vector<uint32_t>{});
  t.computeWrites = j.value("compute_writes", std::vector<uint32_t>{});
  t.presented = j.value("presented", false);
  return t;
}

RdcBinding bindingFromJson(const nlohmann::json& j) {
  RdcBinding b;
  b.name = j.value("name", "");
  b.id = j.value("id", uint64_t(0));
  b.autoName = j.value("auto", false);
  b.kind = j.value("kind", "");
  b.bytes = j.value("bytes", uint64_t(0));
  b.set = j.value("set", 0u);
  b.binding = j.value("binding", 0u);
  b.index = j.value("index", 0u);
  b.stages = j.value("stages", std::vector<std::string>{});
  b.bound = j.contains("set");
  b.offset = j.value("offset", uint64_t(0));
  b.range = j.value("range", uint64_t(0));
  for (const nlohmann::json& m : j.value("members", nlohmann::json::array()))
    if (m.is_array() && m.size() == 3 && m[0].is_string() && m[1].is_number_unsigned() && m[2].is_string())
      b.members.push_back({m[0].get<std::string>(), m[2].get<std::string>(), m[1].get<uint64_t>()});
  return b;
}

// A draw's targets and viewport, as the script reports them for a pass or an event.
void drawStateFromJson(const nlohmann::json& j, RdcPass& p) {
  p.outputs = j.value("outputs", std::vector<std::string>{});
  p.depthTarget = j.value("depthTarget", "");
  const std::vector<double> v = j.value("viewport", std::vector<double>{});
  for (size_t i = 0; i < 4 && i < v.size(); ++i) p.viewport[i] = v[i];
}

}  // namespace

std::optional<TexelFormat> texelFormatOf(const RdcFormat& f) {
  if (f.type == "D32S8") return TexelFormat::D32fS8;
  if (f.type == "D24S8") return TexelFormat::D24S8;
  if (f.type == "R10G10B10A2")
    return !f.bgra && f.compType == "UNorm" ? std::optional(TexelFormat::Rgb10a2Unorm) : std::nullopt;
  // BGRA: 8-bit only, R and B swapped back by the replay script.
  if (f.type != "Regular" || (f.bgra && !(f.compCount == 4 && f.compByteWidth == 1))) return std::nullopt;
  const std::string& c = f.compType;
  if (f.compCount == 1 && c == "Depth") {
    if (f.compByteWidth == 4) return TexelFormat::D32f;
    if (f.compByteWidth == 2) return TexelFormat::D16;
    return std::nullopt;
  }
  if (f.compCount == 1 && f.compByteWidth == 4) {
    if (c == "Float") return TexelFormat::R32f;
    if (c == "UInt") return TexelFormat::R32Uint;
    return std::nullopt;
  }
  if (f.compCount != 4) return std::nullopt;
  if (f.compByteWidth == 1) {
    if (c == "UNormSRGB") return TexelFormat::Rgba8Srgb;
    if (c == "UNorm") return TexelFormat::Rgba8Unorm;
    if (c == "SNorm") return TexelFormat::Rgba8Snorm;
  } else if (f.compByteWidth == 2) {
    if (c == "SNorm") return TexelFormat::Rgba16Snorm;
    if (c == "Float") return TexelFormat::Rgba16f;
  } else if (f.compByteWidth == 4 && c == "Float") {
    return TexelFormat::Rgba32f;
  }
  return std::nullopt;
}

bool listRenderDocCapture(const std::string& rdc, RdcListing& out, std::string& error, const RdcReplayOptions& o) try {
  TempFolder tmp;
  nlohmann::json j;
  if (!runScript(rdc, {"list", rdc}, tmp, o, j, error)) return false;
  out = RdcListing{};
  out.api = j.value("api", "");
  out.driverNote = j.value("driver", "");
  out.provenance = j.value("provenance", nlohmann::json::object());
  out.lastEvent = j.value("lastEvent", 0u);
  std::map<uint64_t, std::string> names;
  for (const nlohmann::json& t : j.at("textures")) {
    out.textures.push_back(textureFromJson(t));
    names[out.textures.back().id] = out.textures.back().name;
  }
  for (const nlohmann::json& p : j.at("passes")) {
    RdcPass pass{p.value("name", ""), p.value("first", 0u), p.value("last", 0u), p.value("depth", 0u), {}};
    for (uint64_t id : p.at("writes").get<std::vector<uint64_t>>())
      pass.writes.push_back(names[id].empty() ? std::string("#") + std::to_string(id) : names[id]);
    for (const nlohmann::json& st : p.value("stores", nlohmann::json::array())) {
      const uint64_t id = st.value("id", uint64_t(0));
      RdcPass::Store store{names[id].empty() ? "#" + std::to_string(id) : names[id], "", ""};
      if (st.contains("store") && st["store"].is_string()) store.store = st["store"];
      if (st.contains("stencil_store") && st["stencil_store"].is_string()) store.stencilStore = st["stencil_store"];
      pass.stores.push_back(store);
    }
    pass.boundAt = p.value("boundAt", 0u);
    for (const nlohmann::json& b : p.value("buffers", nlohmann::json::array())) pass.buffers.push_back(bindingFromJson(b));
    drawStateFromJson(p, pass);
    out.passes.push_back(std::move(pass));
  }
  for (const nlohmann::json& b : j.value("buffers", nlohmann::json::array()))
    out.buffers.push_back({b.value("name", ""), b.value("id", uint64_t(0)), b.value("bytes", uint64_t(0))});
  return true;
} catch (const nlohmann::json::exception& e) {
  return unexpectedResult(rdc, e, error);
}

bool readRenderDocTexels(const std::string& rdc, uint32_t event, const std::vector<std::string>& textures,
                         std::vector<RdcTexels>& out, std::string& error, const RdcReplayOptions& o) try {
  TempFolder tmp;
  std::vector<std::string> args = {"texels", rdc, std::to_string(event), tmp.path.string()};
  args.insert(args.end(), textures.begin(), textures.end());
  nlohmann::json j;
  if (!runScript(rdc, args, tmp, o, j, error)) return false;
  out.clear();
  for (const nlohmann::json& t : j.at("textures")) {
    RdcTexels texels;
    texels.texture = textureFromJson(t);
    texels.event = t.value("event", 0u);
    if (!readBytes(t.value("file", ""), texels.bytes)) {
      error = rdc + ": RenderDoc's replay wrote no texels for " + texels.texture.name;
      return false;
    }
    texels.sampleBytes = t.value("sample_bytes", texels.bytes.size());
    const uint32_t planes = std::max(1u, texels.texture.samples);
    if (texels.sampleBytes * planes != texels.bytes.size()) {
      error = rdc + ": RenderDoc's replay wrote " + std::to_string(texels.bytes.size()) + " bytes for the " +
              std::to_string(planes) + " samples of " + texels.texture.name + ", not " + std::to_string(planes) + " x " +
              std::to_string(texels.sampleBytes);
      return false;
    }
    out.push_back(std::move(texels));
  }
  return true;
} catch (const nlohmann::json::exception& e) {
  return unexpectedResult(rdc, e, error);
}

bool readRenderDocBuffer(const std::string& rdc, uint32_t event, const std::string& buffer, std::vector<uint8_t>& out,
                         std::string& error, const RdcReplayOptions& o, RdcBufferRead* at) try {
  TempFolder tmp;
  const std::string file = (tmp.path / "buffer.bin").string();
  nlohmann::json j;
  if (!runScript(rdc, {"buffer", rdc, std::to_string(event), buffer, file}, tmp, o, j, error)) return false;
  if (!readBytes(file, out)) {
    error = rdc + ": RenderDoc's replay wrote no bytes for buffer " + buffer;
    return false;
  }
  if (at) *at = {j.value("id", uint64_t(0)), j.value("event", 0u)};
  return true;
} catch (const nlohmann::json::exception& e) {
  return unexpectedResult(rdc, e, error);
}

bool readDrawState(const std::string& rdc, const std::vector<uint32_t>& events, bool bytes,
                   std::map<uint32_t, RdcPass>& out, std::string& skipped, std::string& error, const RdcReplayOptions& o) try {
  std::vector<uint32_t> todo(events);
  std::sort(todo.begin(), todo.end());  // forward through the frame: each step replays only what lies between
  todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  skipped.clear();
  while (!todo.empty()) {
    TempFolder tmp;
    std::vector<std::string> args = {"state", rdc, tmp.path.string()};
    if (bytes) args.push_back("--bytes");
    for (uint32_t e : todo) args.push_back(std::to_string(e));
    nlohmann::json j;
    const bool ok = runScript(rdc, args, tmp, o, j, error);
    size_t done = 0;
    for (; done < todo.size(); ++done) {
      const nlohmann::json state =
          nlohmann::json::parse(readText(tmp.path / ("state_" + std::to_string(todo[done]) + ".json")), nullptr, false);
      if (state.is_discarded() || !state.is_object()) break;
      RdcPass& p = out[todo[done]];
      p.boundAt = state.value("event", 0u);
      drawStateFromJson(state, p);
      for (const nlohmann::json& b : state.value("buffers", nlohmann::json::array())) {
        p.buffers.push_back(bindingFromJson(b));
        if (bytes && !readBytes(b.value("file", ""), p.buffers.back().data)) {
          error = rdc + ": RenderDoc's replay wrote no bytes for buffer " + p.buffers.back().name;
          return false;
        }
      }
    }
    todo.erase(todo.begin(), todo.begin() + long(done));
    if (ok || todo.empty()) break;
    if (error.find("crashed") == std::string::npos) return false;
    if (done == 0) {  // even a fresh replay crashes there: leave it out
      skipped += (skipped.empty() ? "" : ", ") + std::to_string(todo.front());
      todo.erase(todo.begin());
    }
  }
  error.clear();
  return true;
} catch (const nlohmann::json::exception& e) {
  return unexpectedResult(rdc, e, error);
}

}  // namespace gb
