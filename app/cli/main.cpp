// gblens: the command-line entry point. Each subcommand lives in its own file (cmd_*.cpp).
#include <cstdio>
#include <string>

#include "app/cli/cli.h"
#include "app/cli/messages.h"

int main(int argc, char** argv) {
  CLI::App app{"gblens: an interactive G-buffer debugger for deferred renderers"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "help for every subcommand");
  std::vector<gb::Command> commands = {
      gb::addRenderCommand(app),
      gb::addViewCommand(app),
      gb::addCaptureCommand(app),
      gb::addCompareCommand(app),
      gb::addProbeCommand(app),
      gb::addInfoCommand(app),
      gb::addErrorCommand(app),
      gb::addBenchCommand(app),
      gb::addStressCommand(app),
      gb::addImportCommand(app),
      gb::addCheckCommand(app),
      gb::addStatsCommand(app),
      gb::addDecomposeCommand(app),
      gb::addAttachCommand(app),
      gb::addMotionCommand(app),
      gb::addFlickerCommand(app),
      gb::addHistoryCommand(app),
  };
  for (int i = 0; i < argc; ++i) gb::commandLine() += (i ? " " : "") + std::string(i ? argv[i] : "gblens");
  // An unknown first word is a mistyped command: name it and the commands there are.
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string list;
    for (gb::Command& c : commands) {
      known |= c.app->get_name() == argv[1];
      list += (list.empty() ? "" : ", ") + c.app->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "gblens: unknown command '%s' (commands: %s; see gblens --help)\n", argv[1], list.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string where;
    int status = 2;
    for (CLI::App* sub : app.get_subcommands()) {
      where = " " + sub->get_name();
      for (gb::Command& c : commands)
        if (c.app == sub) status = c.usageExit;
    }
    std::fprintf(stderr, "gblens%s: %s (see gblens%s --help)\n", where.c_str(), gb::oneLine(e.what()).c_str(), where.c_str());
    return status;
  }
  for (gb::Command& c : commands)
    if (c.app->parsed()) return c.run();
  return 2;
}
