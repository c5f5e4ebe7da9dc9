// SHA-256 digests (OpenSSL's libcrypto) as lowercase hex: capture file checksums, scene and
// light content hashes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace gb {

// Incremental digest: add() any number of times, then hex() once.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void add(const void* data, size_t bytes);
  template <class T>
  void addValue(const T& v) {
    add(&v, sizeof(T));
  }
  void addString(const std::string& s);  // length-prefixed, so "ab"+"c" != "a"+"bc"
  std::string hex();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

std::string sha256Hex(const void* data, size_t bytes);
std::string sha256Hex(const std::string& bytes);
// Digest of a file's bytes; false (and `error` naming the file) when it cannot be read.
bool sha256File(const std::string& path, std::string& hex, std::string& error);

}  // namespace gb
