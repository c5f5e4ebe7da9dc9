// Sequence folders: sequence.json read and checked, SEQ@N resolved, a sequence written frame by frame
// into a temporary folder that takes the destination's place only when every frame is in.
#include "views/capture/sequence.h"

#include <charconv>
#include <cstdio>
#include <filesystem>

#include "renderer/core/json_read.h"
#include "renderer/core/version.h"
#include "views/capture/image_io.h"

namespace fs = std::filesystem;

namespace gb {

static const char* kManifest = "sequence.json";

std::string Sequence::captureDir(size_t i) const { return (fs::path(dir) / frames.at(i).dir).string(); }

int Sequence::find(int64_t number) const {
  for (size_t i = 0; i < frames.size(); ++i)
    if (frames[i].number == number) return int(i);
  return -1;
}

bool isSequence(const std::string& dir) {
  std::error_code ec;
  return fs::is_regular_file(fs::path(dir) / kManifest, ec);
}

// A frame's folder name: a plain name inside the sequence (no separators, not "." or "..").
static bool plainName(const std::string& s) {
  return !s.empty() && s != "." && s != ".." && s.find('/') == std::string::npos && s.find('\\') == std::string::npos;
}

bool loadSequence(const std::string& dir, Sequence& out, std::string& error) {
  const std::string path = (fs::path(dir) / kManifest).string();
  if (!isSequence(dir)) {
    error = dir + ": no sequence.json (not a sequence)";
    return false;
  }
  nlohmann::json m;
  if (!readJsonFile(path, m, error)) return false;
  Sequence s;
  s.dir = dir;
  try {
    JsonIn in(m, path);
    if (in["format"].string() != "gblens-sequence") in["format"].fail("expected \"gblens-sequence\"");
    const int64_t v = in["format_version"].integer(1, 1 << 20);
    if (v > kSequenceFormatVersion)
      in["format_version"].fail("version " + std::to_string(v) + " is newer than this gblens reads (" +
                                std::to_string(kSequenceFormatVersion) + ")");
    JsonIn frames = in["frames"];
    if (frames.size() == 0) frames.fail("no frames");
    for (size_t i = 0; i < frames.size(); ++i) {
      JsonIn f = frames[i];
      SequenceFrame sf;
      sf.number = f["frame"].integer(-(1ll << 40), 1ll << 40);
      sf.dir = f["dir"].string();
      if (!plainName(sf.dir)) f["dir"].fail("expected a folder name inside the sequence");
      if (!s.frames.empty() && sf.number <= s.frames.back().number) f["frame"].fail("frame numbers must increase");
      if (auto t = f.find("time"); t && !t->json().is_null()) sf.time = t->number();
      if (auto j = f.find("jitter"); j && !j->json().is_null()) {
        if (j->size() != 2) j->fail("expected [x, y] in pixels");
        sf.jitter = glm::dvec2((*j)[size_t(0)].number(), (*j)[size_t(1)].number());
      }
      std::error_code ec;
      if (!fs::is_directory(fs::path(dir) / sf.dir, ec)) f["dir"].fail("no folder " + sf.dir + " in the sequence");
      s.frames.push_back(sf);
    }
  } catch (const JsonError& e) {
    error = e.what();
    return false;
  }
  s.manifest = std::move(m);
  out = std::move(s);
  return true;
}

bool resolveSequenceFrame(const std::string& text, std::string& captureDir, std::string& error) {
  error.clear();
  const size_t at = text.rfind('@');
  if (at == std::string::npos || at == 0 || at + 1 == text.size()) return false;
  const std::string seq = text.substr(0, at), num = text.substr(at + 1);
  int64_t n = 0;
  auto r = std::from_chars(num.data(), num.data() + num.size(), n);
  if (r.ec != std::errc() || r.ptr != num.data() + num.size()) return false;  // "name@host" is a folder name
  std::error_code ec;
  if (fs::is_directory(text, ec)) return false;  // a capture folder whose name ends in @N
  Sequence s;
  if (!loadSequence(seq, s, error)) return false;
  const int i = s.find(n);
  if (i < 0) {
    error = text + ": the sequence has no frame " + num + " (frames " + std::to_string(s.frames.front().number) +
            ".." + std::to_string(s.frames.back().number) + ")";
    return false;
  }
  captureDir = s.captureDir(size_t(i));
  return true;
}

static std::string frameDirName(int64_t number) {
  char buf[32];
  std::snprintf(buf, sizeof buf, number < 0 ? "frame_m%04lld" : "frame_%04lld", (long long)(number < 0 ? -number : number));
  return buf;
}

bool writeSequence(const std::string& dir, size_t count,
                   const std::function<bool(size_t i, SequenceEntry& entry, std::string& error)>& produce,
                   const nlohmann::json& extra, std::string& error) {
  if (count == 0) {
    error = dir + ": a sequence needs at least one frame";
    return false;
  }
  return replaceDirectory(dir, kManifest, "sequence", [&](const std::string& tmp, std::string& e) {
    nlohmann::json frames = nlohmann::json::array();
    int64_t previous = 0;
    for (size_t i = 0; i < count; ++i) {
      SequenceEntry entry;
      entry.number = int64_t(i);
      if (!produce(i, entry, e)) return false;
      if (i > 0 && entry.number <= previous) {
        e = dir + ": frame numbers must increase (" + std::to_string(entry.number) + " after " + std::to_string(previous) + ")";
        return false;
      }
      previous = entry.number;
      const std::string name = frameDirName(entry.number);
      if (!writeCapture((fs::path(tmp) / name).string(), entry.frame, entry.meta, e)) return false;
      nlohmann::json f = {{"frame", entry.number}, {"dir", name}};
      f["time"] = entry.time ? nlohmann::json(*entry.time) : nlohmann::json();
      f["jitter"] = entry.jitter ? nlohmann::json::array({entry.jitter->x, entry.jitter->y}) : nlohmann::json();
      frames.push_back(f);
    }
    nlohmann::json m = {{"format", "gblens-sequence"},
                        {"format_version", kSequenceFormatVersion},
                        {"gblens", {{"version", GBLENS_VERSION}, {"git", gitHash()}}},
                        {"frames", frames}};
    for (auto it = extra.begin(); extra.is_object() && it != extra.end(); ++it) m[it.key()] = it.value();
    return writeTextAtomically((fs::path(tmp) / kManifest).string(), m.dump(2) + "\n", e);
  }, error);
}

bool parseFrameRange(const std::string& text, const std::string& flag, int64_t& first, int64_t& last,
                     std::string& error) {
  auto number = [](const std::string& s, int64_t& v) {
    auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
  };
  const size_t dots = text.find("..");
  bool ok = dots == std::string::npos ? number(text, first) && ((last = first), true)
                                      : number(text.substr(0, dots), first) && number(text.substr(dots + 2), last);
  if (!ok || last < first || last - first > 100000) {
    error = flag + " " + text + ": expected a frame range A..B (A <= B) or one frame N";
    return false;
  }
  return true;
}

}  // namespace gb
