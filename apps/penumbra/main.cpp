// penumbra: one CLI for every job. Usage errors exit 2, runtime errors exit 1, each with one
// line on stderr. With no subcommand it runs `render` with its defaults.
#include "Commands.h"

#include "bake/SdfBake.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <string_view>
#include <utility>

namespace {

/// Length of the valid UTF-8 sequence at the start of `s`, or 0 (RFC 3629: no overlong forms, no
/// surrogates, nothing above U+10FFFF).
size_t utf8Length(std::string_view s) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char c = byte(0);
  size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the second byte's range
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c >= 0xE0 && c <= 0xEF) { n = 3; lo = c == 0xE0 ? 0xA0 : 0x80; hi = c == 0xED ? 0x9F : 0xBF; }
  else if (c >= 0xF0 && c <= 0xF4) { n = 4; lo = c == 0xF0 ? 0x90 : 0x80; hi = c == 0xF4 ? 0x8F : 0xBF; }
  if (n == 0 || s.size() < n || byte(1) < lo || byte(1) > hi) return 0;
  for (size_t i = 2; i < n; ++i)
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  return n;
}

/// An error message as one line of text: messages quote what files hold (names, strings), and a
/// control character (an ANSI escape, a newline) or a stray byte must not reach the terminal.
std::string printable(std::string_view message) {
  std::string out;
  for (size_t i = 0; i < message.size();) {
    const auto c = static_cast<unsigned char>(message[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += message[i++];
    } else if (const size_t n = c >= 0x80 ? utf8Length(message.substr(i)) : 0; n > 0) {
      out.append(message.substr(i, n));
      i += n;
    } else {
      out += fmt::format("\\x{:02x}", c);
      ++i;
    }
  }
  return out;
}

// The library names its API's fields in its messages; the command line's options that set them
// are added after the message, once each.
std::string withOptions(std::string message) {
  constexpr std::pair<std::string_view, std::string_view> kFields[] = {
      {"Technique::mapSize", "--shadow-map"}, {"Technique::projection", "--projection"}, {"Technique::filter", "--filter"},
      {"LightShadowSettings::", "the scene file's per-light \"shadow\""}};
  std::string options;
  for (const auto& [field, option] : kFields)
    if (message.find(field) != std::string::npos) options += (options.empty() ? "" : ", ") + std::string(option);
  return options.empty() ? message : message + " [" + options + "]";
}

void printError(const char* message) { std::fprintf(stderr, "penumbra: %s\n", printable(withOptions(message)).c_str()); }

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
  // The version of the build; bench and tune record GL_RENDERER and the clock with every number.
  app.set_version_flag("--version", std::string("penumbra ") + PENUMBRA_VERSION, "print the version and exit");
  penumbra::sdf::installEmbreeBaker();  // the sdf filter's fields: baked with Embree, cached on disk
  std::vector<penumbra::app::Command> commands;
  penumbra::app::registerCommands(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "penumbra: %s (see penumbra --help)\n", printable(e.what()).c_str());
    return 2;
  }
  try {
    for (const penumbra::app::Command& c : commands)
      if (c.app->parsed()) return c.run();
    return commands.front().run();
  } catch (const penumbra::Error& e) {
    printError(e.what());
    return e.kind() == penumbra::ErrorKind::Usage ? 2 : 1;
  } catch (const std::exception& e) {
    printError(e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) { return flushStdout(run(argc, argv)); }
