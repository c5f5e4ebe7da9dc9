// Names of the option values, shared by CLI, UI, manifest and bench.
#include "renderer/options.h"

#include <array>
#include <utility>

namespace gb {

template <class E, size_t N>
using Names = std::array<std::pair<E, const char*>, N>;

static const Names<Path, 2> kPath = {{{Path::TwoPass, "two-pass"}, {Path::SinglePass, "single-pass"}}};
static const Names<Method, 3> kMethod = {
    {{Method::Deferred, "deferred"}, {Method::Forward, "forward"}, {Method::Tiled, "tiled"}}};
static const Names<NormalFormat, 4> kNormal = {{{NormalFormat::Rgba16f, "rgba16f"},
                                                {NormalFormat::Rgba8Snorm, "rgba8-snorm"},
                                                {NormalFormat::OctRg16, "oct-rg16"},
                                                {NormalFormat::Rgb10a2, "rgb10a2"}}};
static const Names<DepthFormat, 2> kDepth = {{{DepthFormat::D32S8, "d32s8"}, {DepthFormat::D24S8, "d24s8"}}};
static const Names<AccumFormat, 3> kAccum = {
    {{AccumFormat::Rgba16f, "rgba16f"}, {AccumFormat::Rgba32f, "rgba32f"}, {AccumFormat::Rgba8, "rgba8"}}};
static const Names<ShadowFormat, 2> kShadow = {{{ShadowFormat::D32f, "d32f"}, {ShadowFormat::D16, "d16"}}};
static const Names<StencilMask, 2> kMask = {{{StencilMask::PerLight, "per-light"}, {StencilMask::Shared, "shared"}}};

template <class E, size_t N>
static const char* lookup(const Names<E, N>& names, E v) {
  for (auto& [e, n] : names)
    if (e == v) return n;
  return "?";
}
template <class E, size_t N>
static bool find(const Names<E, N>& names, const std::string& text, E& out) {
  for (auto& [e, n] : names)
    if (text == n) {
      out = e;
      return true;
    }
  return false;
}

const char* name(Path v) { return lookup(kPath, v); }
const char* name(Method v) { return lookup(kMethod, v); }
const char* name(NormalFormat v) { return lookup(kNormal, v); }
const char* name(DepthFormat v) { return lookup(kDepth, v); }
const char* name(AccumFormat v) { return lookup(kAccum, v); }
const char* name(ShadowFormat v) { return lookup(kShadow, v); }
const char* name(StencilMask v) { return lookup(kMask, v); }
bool parse(const std::string& t, Path& o) { return find(kPath, t, o); }
bool parse(const std::string& t, Method& o) { return find(kMethod, t, o); }
bool parse(const std::string& t, NormalFormat& o) { return find(kNormal, t, o); }
bool parse(const std::string& t, DepthFormat& o) { return find(kDepth, t, o); }
bool parse(const std::string& t, AccumFormat& o) { return find(kAccum, t, o); }
bool parse(const std::string& t, ShadowFormat& o) { return find(kShadow, t, o); }
bool parse(const std::string& t, StencilMask& o) { return find(kMask, t, o); }

}  // namespace gb
