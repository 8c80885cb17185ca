// penumbra: one CLI for every job. Usage errors exit 2, runtime errors exit 1, each with one
// line on stderr. With no subcommand it runs `render` with its defaults.
#include "Commands.h"

#include "bake/SdfBake.h"

#include <penumbra/Error.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

namespace {

// Output that never arrived is a failure: `penumbra list > /dev/full` must not exit 0. stdout
// is block-buffered when it is not a terminal, so most write errors appear only here.
int flushStdout(int code) {
  std::cout.flush();  // synchronised with stdio: its text is in stdout's buffer
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout) {
    std::fprintf(stderr, "penumbra: cannot write to standard output (%s)\n", errno != 0 ? std::strerror(errno) : "write error");
    return code == 0 ? 1 : code;
  }
  return code;
}

int run(int argc, char** argv) {
  CLI::App app{"Penumbra: real-time shadow techniques, rendered and measured against a ray-traced reference.\n"
               "With no subcommand, renders the default scene to penumbra.png."};
  app.require_subcommand(0, 1);
  penumbra::sdf::installEmbreeBaker();  // the sdf filter's fields: baked with Embree, cached on disk
  std::vector<penumbra::app::Command> commands;
  penumbra::app::registerCommands(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "penumbra: %s (see penumbra --help)\n", e.what());
    return 2;
  }
  try {
    for (const penumbra::app::Command& c : commands)
      if (c.app->parsed()) return c.run();
    return commands.front().run();
  } catch (const penumbra::Error& e) {
    std::fprintf(stderr, "penumbra: %s\n", e.what());
    return e.kind() == penumbra::ErrorKind::Usage ? 2 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "penumbra: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) { return flushStdout(run(argc, argv)); }
