// The checked JSON reading of json_read.h: a depth scan before nlohmann parses, every nlohmann
// exception turned into one line, regular files only, and the typed reads of JsonIn.
#include "renderer/core/json_read.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

namespace gb {

using json = nlohmann::json;

bool jsonDepthWithin(std::string_view text, int maxDepth) {
  int depth = 0;
  bool inString = false, escaped = false;
  for (char c : text) {
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      if (++depth > maxDepth) return false;
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return true;
}

// nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ..." without the
// bracketed code, on one line.
static std::string parseMessage(const std::string& what) {
  std::string text = what;
  if (text.rfind("[json.exception.", 0) == 0)
    if (size_t end = text.find("] "); end != std::string::npos) text = text.substr(end + 2);
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  if (text.size() > 300) text = text.substr(0, 300) + "...";
  return text;
}

bool parseJson(std::string_view text, const std::string& where, json& out, std::string& error) {
  if (!jsonDepthWithin(text, kMaxJsonDepth)) {
    error = where + ": nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
    return false;
  }
  try {
    out = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    // parse errors, and out_of_range.406 for numbers beyond a double (1e999, -1e999, 400 digits)
    error = where + ": not valid JSON (" + parseMessage(e.what()) + ")";
    return false;
  } catch (const std::bad_alloc&) {
    error = where + ": too large to parse";
    return false;
  }
  return true;
}

bool isRegularFile(const std::string& path, std::string& error) {
  struct stat st{};
  if (stat(path.c_str(), &st) != 0) {
    error = path + ": cannot read (" + std::strerror(errno) + ")";
    return false;
  }
  if (S_ISREG(st.st_mode)) return true;
  const char* kind = S_ISDIR(st.st_mode)                         ? "a directory"
                     : S_ISFIFO(st.st_mode)                      ? "a FIFO"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                     : S_ISSOCK(st.st_mode)                      ? "a socket"
                                                                 : "not a regular file";
  error = path + ": is " + std::string(kind) + ", not a file";
  return false;
}

bool readRegularFile(const std::string& path, std::string& out, std::string& error, uint64_t maxBytes) {
  if (!isRegularFile(path, error)) return false;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) {
    error = path + ": cannot read";
    return false;
  }
  const std::streamoff size = in.tellg();
  if (size < 0) {
    error = path + ": cannot read";
    return false;
  }
  if (uint64_t(size) > maxBytes) {
    error = path + ": " + std::to_string(size) + " bytes, more than the " + std::to_string(maxBytes >> 20) +
            " MiB such a file can be";
    return false;
  }
  out.resize(size_t(size));
  in.seekg(0);
  if (size && !in.read(out.data(), size)) {
    error = path + ": cannot read";
    return false;
  }
  return true;
}

bool readJsonFile(const std::string& path, json& out, std::string& error) {
  std::string text;
  return readRegularFile(path, text, error, kMaxJsonBytes) && parseJson(text, path, out, error);
}

std::string jsonBrief(const json& v) {
  std::string text;
  try {
    text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  } catch (const std::exception&) {
    text = "?";
  }
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

bool jsonNumber(const json& v, double& out) {
  if (!v.is_number()) return false;
  const double d = v.get<double>();
  if (!std::isfinite(d)) return false;
  out = d;
  return true;
}

bool jsonInteger(const json& v, int64_t lo, int64_t hi, int64_t& out) {
  if (v.is_number_unsigned()) {
    const uint64_t u = v.get<uint64_t>();
    if (u > uint64_t(INT64_MAX) || int64_t(u) < lo || int64_t(u) > hi) return false;
    out = int64_t(u);
    return true;
  }
  if (v.is_number_integer()) {
    const int64_t i = v.get<int64_t>();
    if (i < lo || i > hi) return false;
    out = i;
    return true;
  }
  double d = 0.0;
  // 1e3 is an integer written with an exponent; compare in double before converting (no overflow).
  if (!jsonNumber(v, d) || d != std::floor(d) || d < double(lo) || d > double(hi) || std::abs(d) >= 9.2e18) return false;
  out = int64_t(d);
  return true;
}

void JsonIn::expected(const std::string& type) const {
  fail("expected " + type + ", got " + jsonBrief(*v_));
}

JsonIn JsonIn::operator[](const char* key) const {
  if (!v_->is_object()) expected("an object");
  auto it = v_->find(key);
  const std::string path = path_.empty() ? key : path_ + "." + key;
  if (it == v_->end()) throw JsonError(file_ + ": " + path + ": missing");
  return JsonIn(*it, file_, path);
}

JsonIn JsonIn::operator[](size_t i) const {
  if (!v_->is_array()) expected("an array");
  if (i >= v_->size()) fail("has " + std::to_string(v_->size()) + " elements, no element " + std::to_string(i));
  return JsonIn((*v_)[i], file_, path_ + "[" + std::to_string(i) + "]");
}

std::optional<JsonIn> JsonIn::find(const char* key) const {
  if (!has(key)) return std::nullopt;
  return (*this)[key];
}

size_t JsonIn::size() const {
  if (!v_->is_array()) expected("an array");
  return v_->size();
}

std::vector<std::string> JsonIn::keys() const {
  object();
  std::vector<std::string> out;
  for (auto& [k, unused] : v_->items()) out.push_back(k);
  return out;
}

void JsonIn::object() const {
  if (!v_->is_object()) expected("an object");
}

double JsonIn::number() const {
  double d = 0.0;
  if (!jsonNumber(*v_, d)) expected("a finite number");
  return d;
}

int64_t JsonIn::integer(int64_t lo, int64_t hi) const {
  int64_t i = 0;
  if (!jsonInteger(*v_, lo, hi, i)) expected("an integer " + std::to_string(lo) + ".." + std::to_string(hi));
  return i;
}

bool JsonIn::boolean() const {
  if (!v_->is_boolean()) expected("true or false");
  return v_->get<bool>();
}

std::string JsonIn::string() const {
  if (!v_->is_string()) expected("a string");
  return v_->get<std::string>();
}

glm::dvec3 JsonIn::vec3() const {
  double d[3];
  if (!v_->is_array() || v_->size() != 3 || !jsonNumber((*v_)[0], d[0]) || !jsonNumber((*v_)[1], d[1]) ||
      !jsonNumber((*v_)[2], d[2]))
    expected("3 finite numbers");
  return {d[0], d[1], d[2]};
}

std::vector<std::string> JsonIn::strings() const {
  std::vector<std::string> out;
  for (size_t i = 0; i < size(); ++i) out.push_back((*this)[i].string());
  return out;
}

std::vector<uint32_t> JsonIn::u32s() const {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < size(); ++i) out.push_back((*this)[i].u32());
  return out;
}

}  // namespace gb
