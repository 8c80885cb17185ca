#pragma once
// Each subcommand registers its options and its action; main() runs the chosen one.
#include <CLI/CLI.hpp>

#include <functional>
#include <vector>

namespace penumbra::app {

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

void addRenderCommand(CLI::App& app, std::vector<Command>& commands);
void addListCommand(CLI::App& app, std::vector<Command>& commands);
void addViewCommand(CLI::App& app, std::vector<Command>& commands);
void addCompareCommand(CLI::App& app, std::vector<Command>& commands);
void addBenchCommand(CLI::App& app, std::vector<Command>& commands);
void addCacheCommand(CLI::App& app, std::vector<Command>& commands);
void addTuneCommand(CLI::App& app, std::vector<Command>& commands);

/// All subcommands, in the order --help lists them. The first one runs when none is named.
inline void registerCommands(CLI::App& app, std::vector<Command>& commands) {
  addRenderCommand(app, commands);
  addCompareCommand(app, commands);
  addBenchCommand(app, commands);
  addTuneCommand(app, commands);
  addViewCommand(app, commands);
  addListCommand(app, commands);
  addCacheCommand(app, commands);
}

}  // namespace penumbra::app
