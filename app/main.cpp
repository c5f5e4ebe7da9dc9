// gblens: the command-line entry point. Each subcommand lives in its own file (cmd_*.cpp).
#include <cstdio>

#include "app/cli.h"

int main(int argc, char** argv) {
  CLI::App app{"gblens: an interactive G-buffer debugger for deferred renderers"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "help for every subcommand");
  std::vector<gb::Command> commands = {
      gb::addRenderCommand(app),
      gb::addErrorCommand(app),
      gb::addBenchCommand(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string where;
    for (CLI::App* sub : app.get_subcommands()) where = " " + sub->get_name();
    std::fprintf(stderr, "gblens%s: %s (see gblens%s --help)\n", where.c_str(), e.what(), where.c_str());
    return 2;
  }
  for (gb::Command& c : commands)
    if (c.app->parsed()) return c.run();
  return 2;
}
