// The pixel dossier as JSON (exact: doubles round-trip) and as text for `gblens probe`.
#include <cmath>
#include <cstdio>

#include "views/analysis/probe.h"

namespace gb {

static nlohmann::json v3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
static nlohmann::json v4(const glm::dvec4& v) { return {v.x, v.y, v.z, v.w}; }

static std::string hex(uint32_t bits, const std::string& type) {
  int digits = type == "u8" || type == "i8" ? 2 : type == "u16" || type == "i16" || type == "f16" ? 4 : 8;
  char buf[16];
  std::snprintf(buf, sizeof(buf), "0x%0*x", digits, bits);
  return buf;
}

static nlohmann::json position(const ProbePosition& p) {
  if (!p.valid) return nullptr;
  return {{"eye", v3(p.eye)}, {"world", v3(p.world)}};
}

static nlohmann::json opt(bool has, nlohmann::json v) { return has ? v : nlohmann::json(nullptr); }

static nlohmann::json channelsJson(const std::vector<ProbeChannel>& channels, const std::string& type) {
  nlohmann::json ch = nlohmann::json::array();
  for (const ProbeChannel& c : channels) ch.push_back({{"name", c.name}, {"bits", hex(c.bits, type)}, {"value", c.value}});
  return ch;
}

// Every screen target's raw channels (bits and value), or why it is absent; a multisampled
// target's every sample and their spread (null for one sample).
static nlohmann::json targetsJson(const PixelDossier& d) {
  nlohmann::json targets = nlohmann::json::array();
  for (const ProbeTarget& t : d.targets) {
    nlohmann::json e = {{"target", t.target}};
    if (!t.present) {
      e["absent"] = t.absent;
    } else {
      e["type"] = t.type;
      e["encoding"] = t.encoding;
      e["channels"] = channelsJson(t.channels, t.type);
      e["samples"] = e["spread"] = nullptr;
      if (!t.samples.empty()) {
        e["samples"] = nlohmann::json::array();
        for (const auto& s : t.samples) e["samples"].push_back(channelsJson(s, t.type));
        e["spread"] = t.spread;
      }
    }
    targets.push_back(e);
  }
  return targets;
}

// The shadow-map lookup: bias, and when valid the receiver, the four texels and the filter.
static nlohmann::json shadowJson(const ProbeShadow& s) {
  nlohmann::json sm = {{"valid", s.valid}, {"note", s.note}, {"bias", {{"constant", s.biasConstant}, {"slope", s.biasSlope}, {"clamp", s.biasClamp}}}};
  if (!s.valid) return sm;
  nlohmann::json texels = nlohmann::json::array();
  for (int k = 0; k < 4; ++k)
    texels.push_back({{"texel", {s.x0 + (k & 1), s.y0 + (k >> 1)}}, {"stored_depth", s.stored[k]},
                      {"weight", s.weight[k]}, {"lit", s.lit[k]}, {"outside", s.outside[k]}});
  sm["light_clip"] = v3(s.lightClip);
  sm["receiver_depth"] = s.receiverDepth;
  sm["texel_coordinates"] = {s.texel.x, s.texel.y};
  sm["texels"] = texels;
  sm["nearest_margin"] = s.nearestMargin;
  sm["filtered"] = s.filtered;
  sm["stored_shadow"] = s.storedShadow;
  return sm;
}

// Why each light that could matter lights the pixel or not.
static nlohmann::json ledgerJson(const LightLedger& l) {
  nlohmann::json entries = nlohmann::json::array();
  for (const LedgerEntry& e : l.entries) {
    nlohmann::json j = {{"light", e.light}, {"fate", e.fate}, {"why", e.why}, {"contribution", v3(e.contribution)}};
    if (e.light == "point")
      j.update({{"index", e.index}, {"drawn_as", e.drawnAs}, {"distance", e.distance}, {"radius", e.radius}});
    j["n_dot_l"] = e.nDotL;
    entries.push_back(j);
  }
  return {{"rule", l.rule}, {"not_listed", l.notListed}, {"entries", entries}};
}

// Sun and ambient, each point light whose volume the ray meets, the coverage counts.
static nlohmann::json lightingJson(const PixelDossier& d) {
  nlohmann::json lights = nlohmann::json::array();
  for (const ProbeLight& l : d.lights)
    lights.push_back({{"index", l.index},
                      {"class", l.lightClass},
                      {"eye_position", v3(l.eyePosition)},
                      {"radius", l.radius},
                      {"color", v3(l.color)},
                      {"volume_enter", l.enter},
                      {"volume_exit", l.exit},
                      {"distance", l.distance},
                      {"distance_over_radius", l.distance / l.radius},
                      {"attenuation", l.attenuation},
                      {"stencil_pass", l.stencilPass},
                      {"contribution", v3(l.contribution)}});
  return {{"view_direction", v3(d.viewDirection)},
          {"directional", v3(d.directional)},
          {"point_lights", lights},
          {"covering_lights", d.lights.size()},
          {"shaded_lights", d.shadedLights},
          {"coverage_full", d.coverageFull < 0 ? nlohmann::json(nullptr) : nlohmann::json(d.coverageFull)},
          {"coverage_masked", d.coverageMasked < 0 ? nlohmann::json(nullptr) : nlohmann::json(d.coverageMasked)},
          {"point_light_total", v3(d.pointLightTotal)},
          {"ledger", ledgerJson(d.ledger)}};
}

// Every layout quantity decoded, and every position the layout allows.
static nlohmann::json quantitiesJson(const PixelDossier& d) {
  nlohmann::json qs = nlohmann::json::array();
  for (const ProbeQuantity& q : d.quantities) {
    nlohmann::json e = {{"name", q.name}, {"kind", q.kind}, {"target", q.target}, {"encoding", q.encoding},
                        {"space", q.space}, {"present", q.present}, {"values", q.values}};
    if (q.eyeDepth) e["eye_depth"] = *q.eyeDepth;
    if (!q.note.empty()) e["note"] = q.note;
    e["samples"] = nullptr;  // its target multisampled: each sample decoded
    if (!q.sampleValues.empty()) {
      e["samples"] = nlohmann::json::array();
      for (size_t k = 0; k < q.sampleValues.size(); ++k) {
        nlohmann::json sample = {{"values", q.sampleValues[k]}};
        if (!q.sampleNotes[k].empty()) sample["note"] = q.sampleNotes[k];
        e["samples"].push_back(sample);
      }
    }
    qs.push_back(e);
  }
  return qs;
}
static nlohmann::json reconstructionsJson(const PixelDossier& d) {
  nlohmann::json rs = nlohmann::json::array();
  for (const ProbeReconstruction& r : d.reconstructions) {
    nlohmann::json e = {{"quantity", r.quantity}, {"method", r.method}, {"valid", r.valid}};
    if (r.valid) {
      e["eye"] = v3(r.eye);
      e["world"] = v3(r.world);
      e["world_space"] = r.worldSpace;
    }
    if (r.hasStored) e["to_stored"] = {{"distance", r.toStored}, {"ulps", r.toStoredUlps}, {"ulp_of", r.ulpOf}};
    rs.push_back(e);
  }
  return rs;
}

nlohmann::json dossierJson(const PixelDossier& d) {
  nlohmann::json j = {{"format", "gblens-probe"}, {"version", kProbeJsonVersion}, {"pixel", {d.x, d.y}},
                      {"size", {d.width, d.height}}, {"native", d.native},
                      {"error", d.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(d.error)}};
  for (const char* k : {"missing", "targets", "quantities", "reconstructions", "decoded", "position", "shadow_map",
                        "lighting", "hdr", "final"})
    j[k] = nullptr;
  if (!d.error.empty()) return j;
  j["missing"] = d.missing;
  j["targets"] = targetsJson(d);
  j["quantities"] = quantitiesJson(d);
  j["reconstructions"] = reconstructionsJson(d);
  // Through the layout, for every layout: null where it holds no such quantity.
  j["decoded"] = {{"geometry", d.geometry},
                  {"albedo", opt(d.hasAlbedo, v3(d.albedo))},
                  {"specular", opt(d.hasSpecular, d.specular)},
                  {"unlit", opt(d.hasNormal, d.unlit)},
                  {"normal", opt(d.hasNormal && !d.unlit, v3(d.normal))},
                  {"normal_stored", opt(d.hasNormal, v3(d.normalStored))},
                  {"normal_length_error", opt(d.hasNormal, d.normalLengthError)},
                  {"shadow", opt(d.hasShadow, d.shadow)},
                  {"eye_depth", opt(d.hasEyeDepth, d.eyeDepth)},
                  {"hardware_depth", opt(d.hasHardwareDepth, d.hardwareDepth)},
                  {"stencil", opt(d.hasStencil, d.stencil)}};
  const bool both = d.fromEyeDepth.valid && d.fromHardwareDepth.valid;
  j["position"] = {{"source", d.positionSource},
                   {"from_eye_depth", position(d.fromEyeDepth)},
                   {"from_hardware_depth", position(d.fromHardwareDepth)},
                   {"difference", opt(both, d.positionDifference)},
                   {"eye_depth_ulps", opt(both, d.eyeDepthUlps)},
                   {"hardware_depth_ulps", opt(both, d.hardwareDepthUlps)}};
  if (d.lightingNote.empty()) j["lighting"] = lightingJson(d);
  else if (d.native) (j["lighting"] = lightingJson(d))["note"] = d.lightingNote;
  else j["lighting"] = {{"note", d.lightingNote}};
  // gblens's own frame only: its shadow map, hdr and final (another renderer's mean something else).
  if (!d.native) return j;
  j["shadow_map"] = shadowJson(d.shadowMap);
  const bool expected = d.geometry && d.lightingNote.empty();
  // Without geometry the skybox wrote hdr: there is no lighting to expect.
  j["hdr"] = {{"stored", opt(d.hasHdr, v4(d.hdr))},
              {"expected", opt(expected, v3(d.hdrExpected))},
              {"residual", opt(d.hasHdr && expected, v3(glm::dvec3(d.hdr) - d.hdrExpected))}};
  j["final"] = {{"stored", opt(d.hasFinal, v4(d.finalColor))},
                {"expected", opt(d.hasHdr, v3(d.finalExpected))},
                {"expected_srgb8", opt(d.hasHdr, {d.finalExpectedSrgb8.x, d.finalExpectedSrgb8.y, d.finalExpectedSrgb8.z})}};
  return j;
}

// ---- text ----------------------------------------------------------------------------------------

static std::string f9(double v) {
  char b[40];
  std::snprintf(b, sizeof(b), "%.9g", v);
  return b;
}
static std::string t3(const glm::dvec3& v) {
  char b[128];
  std::snprintf(b, sizeof(b), "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
  return b;
}

// What is missing and every target's raw channels.
static std::string targetsText(const PixelDossier& d) {
  std::string o;
  char line[512];
  if (!d.missing.empty()) {
    o += "missing:";
    for (const std::string& m : d.missing) o += " " + m;
    o += "\n";
  }
  o += "\nraw stored values\n";
  for (const ProbeTarget& t : d.targets) {
    if (!t.present) {
      o += "  " + t.target + ": " + t.absent + "\n";
      continue;
    }
    o += "  " + t.target + " (" + t.type + " " + t.encoding + ")\n";
    for (const ProbeChannel& c : t.channels) {
      std::snprintf(line, sizeof(line), "    %-10s %-10s = %s\n", c.name.c_str(), hex(c.bits, t.type).c_str(), f9(c.value).c_str());
      o += line;
    }
    for (size_t k = 0; k < t.samples.size(); ++k) {  // a multisampled target: every sample, then the spread
      o += "    sample " + std::to_string(k) + ":";
      for (const ProbeChannel& c : t.samples[k]) o += " " + hex(c.bits, t.type) + " (" + f9(c.value) + ")";
      o += "\n";
    }
    if (!t.spread.empty()) {
      o += "    spread:  ";
      for (double s : t.spread) o += " " + f9(s);
      o += "\n";
    }
  }
  return o;
}

// Every quantity of the layout, decoded as its view shows it, and every position it allows.
static std::string quantitiesText(const PixelDossier& d) {
  std::string o = "\nquantities (as the layout declares them)\n";
  for (const ProbeQuantity& q : d.quantities) {
    std::string v;
    for (double x : q.values) v += (v.empty() ? "" : ", ") + f9(x);
    o += "  " + q.target + "." + q.name + " (" + q.kind + (q.encoding.empty() ? "" : ", " + q.encoding) + ")  " +
         (q.present ? (v.empty() ? "" : q.space + " (" + v + ")") + (q.eyeDepth ? "  eye depth " + f9(*q.eyeDepth) : "") +
                          (q.note.empty() ? "" : "  " + q.note)
                    : std::string("-")) +
         "\n";
    for (size_t k = 0; k < q.sampleValues.size(); ++k) {
      std::string sv;
      for (double x : q.sampleValues[k]) sv += (sv.empty() ? "" : ", ") + f9(x);
      o += "    sample " + std::to_string(k) + ": " + (sv.empty() ? "" : "(" + sv + ")") +
           (q.sampleNotes[k].empty() ? "" : "  " + q.sampleNotes[k]) + "\n";
    }
  }
  bool any = false;
  for (const ProbeReconstruction& r : d.reconstructions) {
    if (!r.valid) continue;
    if (!any) o += "\npositions (eye space | " + r.worldSpace + ")\n";
    any = true;
    o += "  " + r.quantity + " (" + r.method + ")  " + t3(r.eye) + " | " + t3(r.world);
    if (r.hasStored) o += "   to the stored position " + f9(r.toStored) + " (" + f9(r.toStoredUlps) + " " + r.ulpOf + " ulps)";
    o += "\n";
  }
  return o;
}

// gblens's frame: its decoded G-buffer and both reconstructed positions.
static std::string decodedText(const PixelDossier& d) {
  std::string o = "\ndecoded\n";
  o += "  geometry        " + std::string(d.geometry ? "yes" : "no (sky)") + "\n";
  o += "  albedo          " + (d.hasAlbedo ? t3(d.albedo) + "   specular " + f9(d.specular) : "-") + "\n";
  o += "  normal          " + (!d.hasNormal ? std::string("-")
                             : d.unlit   ? std::string("none: unlit (KHR_materials_unlit), shown as its albedo")
                                         : t3(d.normal) + "   stored length error " + f9(d.normalLengthError)) +
       "\n";
  o += "  shadow          " + (d.hasNormal ? f9(d.shadow) : "-") + "\n";
  o += "  eye depth       " + (d.hasEyeDepth ? f9(d.eyeDepth) : "-") + "\n";
  o += "  hardware depth  " + (d.hasHardwareDepth ? f9(d.hardwareDepth) : "-") + "\n";
  if (d.hasHardwareDepth)
    o += "  stencil         " + std::to_string(d.stencil) + " (bit 7 geometry: " + ((d.stencil & 0x80) ? "set" : "clear") +
         ", low bits " + std::to_string(d.stencil & 0x7F) + ")\n";
  o += "\npositions (eye space | world space); the lighting used " + d.positionSource + "\n";
  for (auto [label, p] : {std::pair{"from eye depth     ", &d.fromEyeDepth}, {"from hardware depth", &d.fromHardwareDepth}})
    o += std::string("  ") + label + " " + (p->valid ? t3(p->eye) + " | " + t3(p->world) : std::string("-")) + "\n";
  o += "  difference          " + f9(d.positionDifference) + " scene units; eye depth " + f9(d.eyeDepthUlps) +
       " ulps, hardware depth " + f9(d.hardwareDepthUlps) + " ulps\n";
  return o;
}

// The shadow-map lookup and the point lights met by the ray.
static std::string lightingText(const PixelDossier& d) {
  std::string o;
  char line[512];
  const ProbeShadow& s = d.shadowMap;
  if (!d.lightingNote.empty()) o += "\nlighting: " + d.lightingNote + "\n";
  o += "\nshadow map: " + s.note + "\n";
  if (s.valid) {
    o += "  receiver depth " + f9(s.receiverDepth) + " at texel " + f9(s.texel.x) + ", " + f9(s.texel.y) + "; bias constant " +
         f9(s.biasConstant) + " slope " + f9(s.biasSlope) + " clamp " + f9(s.biasClamp) + "\n";
    for (int k = 0; k < 4; ++k) {
      std::snprintf(line, sizeof(line), "  texel %5d,%-5d stored %-12s weight %-10s %s%s\n", s.x0 + (k & 1), s.y0 + (k >> 1),
                    f9(s.stored[k]).c_str(), f9(s.weight[k]).c_str(), s.lit[k] ? "lit" : "shadowed",
                    s.outside[k] ? " (border)" : "");
      o += line;
    }
    o += "  filtered " + f9(s.filtered) + " (stored shadow " + f9(s.storedShadow) + "), nearest texel margin " +
         f9(s.nearestMargin) + "\n";
  }
  auto count = [](int64_t v) { return v < 0 ? std::string("n/a") : std::to_string(v); };
  o += "\npoint lights whose volume the pixel's ray meets: " + std::to_string(d.lights.size()) + " (coverage_full " +
       count(d.coverageFull) + "); shaded " + std::to_string(d.shadedLights) + " (coverage_masked " +
       count(d.coverageMasked) + ")\n";
  for (const ProbeLight& l : d.lights) {
    std::snprintf(line, sizeof(line), "  light %-5u %-10s d/r %-10s atten %-10s %-7s %s\n", l.index, l.lightClass.c_str(),
                  f9(l.distance / l.radius).c_str(), f9(l.attenuation).c_str(), l.stencilPass ? "shaded" : "culled",
                  t3(l.contribution).c_str());
    o += line;
  }
  o += "  point-light total   " + t3(d.pointLightTotal) + "\n";
  o += "  directional+ambient " + t3(d.directional) + "\n";
  if (!d.ledger.entries.empty()) {
    o += "\nwhy is this pixel lit (" + d.ledger.rule + "; " + std::to_string(d.ledger.notListed) + " farther not listed):\n";
    for (const LedgerEntry& e : d.ledger.entries) {
      const std::string name = e.light == "sun" ? "sun" : "light " + std::to_string(e.index);
      std::snprintf(line, sizeof(line), "  %-11s %-15s %s: %s\n", name.c_str(), e.fate.c_str(), t3(e.contribution).c_str(),
                    e.why.c_str());
      o += line;
      if (!e.drawnAs.empty()) o += "              drawn as: " + e.drawnAs + "\n";
    }
  }
  return o;
}

// The stored hdr and final against what the dossier expects.
static std::string outputsText(const PixelDossier& d) {
  std::string o;
  if (d.hasHdr) {
    o += "\nhdr stored          " + t3(glm::dvec3(d.hdr)) + " a " + f9(d.hdr.w) + (d.geometry ? "" : " (the skybox)") + "\n";
    if (d.geometry && d.lightingNote.empty()) {
      o += "  expected          " + t3(d.hdrExpected) + " (directional + point lights; fairy sprites not included)\n";
      o += "  residual          " + t3(glm::dvec3(d.hdr) - d.hdrExpected) + "\n";
    }
  }
  if (d.hasFinal) {
    o += "final (linear)      " + t3(glm::dvec3(d.finalColor)) + " a " + f9(d.finalColor.w) + "\n";
    if (d.hasHdr) {
      char line[512];
      std::snprintf(line, sizeof(line), "  toneMap(hdr)      %s = sRGB 0x%02x 0x%02x 0x%02x\n", t3(d.finalExpected).c_str(),
                    d.finalExpectedSrgb8.x, d.finalExpectedSrgb8.y, d.finalExpectedSrgb8.z);
      o += line;
    }
  }
  return o;
}

std::string dossierText(const PixelDossier& d) {
  char line[512];
  std::snprintf(line, sizeof(line), "pixel %u,%u of %ux%u\n", d.x, d.y, d.width, d.height);
  std::string o = line;
  if (!d.error.empty()) return o + "error: " + d.error + "\n";
  if (!d.native) return o + targetsText(d) + quantitiesText(d) + (d.lightingNote.empty() ? lightingText(d) : "\nlighting: " + d.lightingNote + "\n");
  return o + targetsText(d) + quantitiesText(d) + decodedText(d) + lightingText(d) + outputsText(d);
}

}  // namespace gb
