// Reading the JSON that users and files hand gblens (layouts, camera sidecars, capture manifests,
// lights.json, the RenderDoc replay's result): one parser with a nesting and a size limit, and one
// checked accessor whose every typed read names the file, the path in the document and the type
// it expected, so that no malformed value ends the program or is silently wrapped or clamped.
#pragma once
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace gb {

// Deeper than any layout or manifest gblens writes (the embedded layout of a manifest is about 8
// levels), shallow enough that every recursive walk (parameter resolution, dump) stays far from
// the stack's end, AddressSanitizer's larger frames included.
constexpr int kMaxJsonDepth = 100;
// A layout or manifest is kilobytes; a file far larger is not one (or is /dev/zero).
constexpr uint64_t kMaxJsonBytes = 64ull << 20;

// Whether `text`'s arrays and objects nest at most maxDepth deep (a scan of the bytes, strings
// skipped: no recursion, so it is safe on any input; the glTF loader runs it too).
bool jsonDepthWithin(std::string_view text, int maxDepth);

// Parses `text`. False with "WHERE: not valid JSON (...)", "WHERE: nested deeper than N levels" or a
// number out of range, one line each; never throws.
bool parseJson(std::string_view text, const std::string& where, nlohmann::json& out, std::string& error);

// Reads a regular file (not a directory, FIFO, socket or device) of at most maxBytes, whole.
bool readRegularFile(const std::string& path, std::string& out, std::string& error, uint64_t maxBytes);
// Whether `path` (after symlinks) is a regular file; else false with "PATH: is a directory" (FIFO,
// device, ...) or "PATH: cannot read (...)".
bool isRegularFile(const std::string& path, std::string& error);

// readRegularFile (kMaxJsonBytes) + parseJson, the message naming `path`.
bool readJsonFile(const std::string& path, nlohmann::json& out, std::string& error);

// A value as messages show it: its JSON text, cut to about 60 characters.
std::string jsonBrief(const nlohmann::json& v);

// The one test of each expected type. Numbers are finite (nlohmann refuses 1e999 while parsing;
// values built in memory may not be); integers are exact (a JSON integer, or a number with no
// fraction) and within [lo, hi] (so 4294967296 is never a channel and 2^64-1 never an offset).
bool jsonNumber(const nlohmann::json& v, double& out);
bool jsonInteger(const nlohmann::json& v, int64_t lo, int64_t hi, int64_t& out);

// Thrown by JsonIn's reads: the one-line message.
struct JsonError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A value in a document and where it is. Every read checks the type (and range) and throws
// JsonError("FILE: PATH: expected TYPE, got VALUE") otherwise; a missing member reads as
// "FILE: PATH: missing".
class JsonIn {
 public:
  JsonIn(const nlohmann::json& root, std::string file) : v_(&root), file_(std::move(file)) {}

  bool has(const char* key) const { return v_->is_object() && v_->contains(key); }
  JsonIn operator[](const char* key) const;  // a member; throws when missing or not an object
  JsonIn operator[](size_t i) const;         // an element of an array
  std::optional<JsonIn> find(const char* key) const;
  size_t size() const;                       // of an array (throws otherwise)
  std::vector<std::string> keys() const;     // of an object (throws otherwise)

  double number() const;
  int64_t integer(int64_t lo, int64_t hi) const;
  uint32_t u32() const { return uint32_t(integer(0, 0xFFFFFFFFll)); }
  bool boolean() const;
  std::string string() const;
  glm::dvec3 vec3() const;                   // [x, y, z]
  std::vector<std::string> strings() const;  // an array of strings
  std::vector<uint32_t> u32s() const;        // an array of unsigned 32-bit integers
  void object() const;                       // throws unless an object

  const nlohmann::json& json() const { return *v_; }
  std::string where() const { return path_.empty() ? file_ : file_ + ": " + path_; }
  [[noreturn]] void fail(const std::string& what) const { throw JsonError(where() + ": " + what); }

 private:
  JsonIn(const nlohmann::json& v, std::string file, std::string path)
      : v_(&v), file_(std::move(file)), path_(std::move(path)) {}
  [[noreturn]] void expected(const std::string& type) const;
  const nlohmann::json* v_;
  std::string file_, path_;
};

}  // namespace gb
