#pragma once
// The viewer's scripted mode (`penumbra view --script FILE`): one action per line, `#` starts a
// comment. Actions run in order at the start of a frame; `wait N`, `screenshot` and
// `wait-heatmap` let frames pass, everything else takes effect before the next frame is drawn.
// The viewer exits after the last action. docs/viewer.md lists the actions.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::viewer {

struct ScriptAction {
  int line = 0;                   ///< 1-based line in the script file
  std::string verb;               ///< "filter", "set", "wait", ...
  std::vector<std::string> args;  ///< whitespace-separated words after the verb
  std::string where;              ///< "file:line" for messages
};

/// Parses a script; checks every verb and its argument count/format, so a typo fails before
/// the first frame. Throws a usage Error naming "file:line".
std::vector<ScriptAction> parseScript(std::string_view text, const std::string& fileName);
std::vector<ScriptAction> loadScript(const std::filesystem::path& path);

/// One line per verb: "verb ARGS  meaning" (for --help and docs).
std::string scriptHelp();

/// Parses a whole-number argument of an action; throws a usage Error naming the action.
int scriptInt(const ScriptAction& a, size_t index, int min, int max);
/// Parses a finite number argument; throws a usage Error naming the action.
float scriptFloat(const ScriptAction& a, size_t index);

}  // namespace penumbra::viewer
