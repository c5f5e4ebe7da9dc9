// SHA-256 through OpenSSL's EVP interface (libssl-dev), streamed for files.
#include "renderer/core/sha256.h"

#include <openssl/evp.h>

#include <cstdio>
#include <vector>

#include "renderer/core/assert.h"

namespace gb {

struct Sha256::State {
  EVP_MD_CTX* ctx = nullptr;
};

Sha256::Sha256() : state_(new State) {
  state_->ctx = EVP_MD_CTX_new();
  GB_ASSERT(state_->ctx);
  int ok = EVP_DigestInit_ex(state_->ctx, EVP_sha256(), nullptr);
  GB_ASSERT(ok == 1);
}

Sha256::~Sha256() { EVP_MD_CTX_free(state_->ctx); }

void Sha256::add(const void* data, size_t bytes) {
  if (!bytes) return;
  int ok = EVP_DigestUpdate(state_->ctx, data, bytes);
  GB_ASSERT(ok == 1);
}

void Sha256::addString(const std::string& s) {
  addValue(uint64_t(s.size()));
  add(s.data(), s.size());
}

std::string Sha256::hex() {
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  int ok = EVP_DigestFinal_ex(state_->ctx, md, &n);
  GB_ASSERT(ok == 1);
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < n; ++i) {
    out += digits[md[i] >> 4];
    out += digits[md[i] & 15];
  }
  return out;
}

std::string sha256Hex(const void* data, size_t bytes) {
  Sha256 h;
  h.add(data, bytes);
  return h.hex();
}

std::string sha256Hex(const std::string& bytes) { return sha256Hex(bytes.data(), bytes.size()); }

bool sha256File(const std::string& path, std::string& hex, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    error = path + ": cannot open";
    return false;
  }
  Sha256 h;
  std::vector<char> buf(1 << 20);
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) h.add(buf.data(), n);
  bool ok = !std::ferror(f);
  std::fclose(f);
  if (!ok) {
    error = path + ": read error";
    return false;
  }
  hex = h.hex();
  return true;
}

}  // namespace gb
