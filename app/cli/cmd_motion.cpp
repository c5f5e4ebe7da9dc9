// gblens motion SEQ [--json] [-o DIR] [--motion NAME] [--bound PX]: a sequence's motion vectors checked
// by reprojection, pair by pair, and the convention they follow set against the layout's
// (views/analysis/temporal.h, docs/temporal.md). Exit 0: they follow it; 1: a finding; 2: bad input.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/cli/cli.h"
#include "app/cli/messages.h"
#include "views/analysis/temporal.h"
#include "views/capture/exr.h"
#include "views/capture/image_io.h"

namespace gb {

namespace {
struct MotionArgs {
  std::string sequence, output, motion;
  double bound = 0.0;
  bool json = false;
};

int motionFail(const std::string& message) {
  std::fprintf(stderr, "gblens motion: %s\n", oneLine(message).c_str());
  return 2;
}

// DIR: motion.json and, per pair, pair_NNNN.exr (the error in pixels and the class), written atomically.
bool writeMotionMaps(const std::string& dir, const MotionReport& r, const nlohmann::json& report, std::string& error) {
  return replaceDirectory(dir, "motion.json", "motion report", [&](const std::string& tmp, std::string& e) {
    for (const MotionPair& p : r.pairs) {
      CpuImage both;
      both.name = "motion", both.type = PixelType::F32, both.width = p.errorMap.width, both.height = p.errorMap.height;
      both.channels = {"error", "class"};
      both.data.resize(size_t(both.width) * both.height * 8);
      float* o = reinterpret_cast<float*>(both.data.data());
      const float* err = reinterpret_cast<const float*>(p.errorMap.data.data());
      const uint32_t* cls = reinterpret_cast<const uint32_t*>(p.classMap.data.data());
      for (size_t i = 0; i < size_t(both.width) * both.height; ++i) o[2 * i] = err[i], o[2 * i + 1] = float(cls[i]);
      char name[64];
      std::snprintf(name, sizeof name, "pair_%04lld.exr", (long long)p.current);
      if (!writeExr((std::filesystem::path(tmp) / name).string(), both, e)) return false;
    }
    return writeTextAtomically((std::filesystem::path(tmp) / "motion.json").string(), report.dump(2) + "\n", e);
  }, error);
}
}  // namespace

Command addMotionCommand(CLI::App& root) {
  auto o = std::make_shared<MotionArgs>();
  CLI::App* cmd = root.add_subcommand(
      "motion", "check a sequence's motion vectors by reprojection: the convention they follow, the error, what moves");
  cmd->add_option("SEQUENCE", o->sequence, "a sequence folder (capture --sequence, import --frames)")->required();
  cmd->add_option("--motion", o->motion, "the motion quantity to check (default: the layout's first)");
  cmd->add_option("--bound", o->bound, "the agreement bound in pixels (default: derived from the frames' precision)")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_option("-o,--output", o->output, "a folder for motion.json and each pair's error and class map (EXR)");
  cmd->add_flag("--json", o->json, "print the report as JSON (docs/schemas/motion.schema.json)");
  return {cmd, [o]() -> int {
            Sequence seq;
            std::string error;
            if (!loadSequence(o->sequence, seq, error)) return motionFail(error);
            if (!o->output.empty() && !checkFolderDestination("-o", o->output, "motion.json", "motion report", error))
              return motionFail(error);
            MotionSequenceOptions mo;
            mo.motion = o->motion;
            mo.inlierPixels = o->bound;
            mo.progress = terminalProgress();
            MotionReport r;
            if (!checkMotionSequence(seq, mo, r, error)) return motionFail(error);
            const nlohmann::json j = motionReportJson(r, o->sequence);
            if (!o->output.empty() && !writeMotionMaps(o->output, r, j, error)) return motionFail(error);
            if (o->json)
              std::printf("%s\n", j.dump(2).c_str());
            else
              std::printf("sequence %s, motion quantity %s\n%s", o->sequence.c_str(), r.motion.c_str(), motionReportText(r).c_str());
            return r.verdict == "differs" ? 1 : 0;
          }};
}

}  // namespace gb
