#include "viewer/Script.h"

#include "viewer/LightEdit.h"

#include <penumbra/Error.h>
#include <penumbra/Shadows.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <span>
#include <sstream>

namespace penumbra::viewer {
namespace {

struct Verb {
  std::string_view name;
  size_t minArgs, maxArgs;
  std::string_view usage, help;
};

// The panels' script names (Viewer.h kPanels; checked against them by the viewer's test).
constexpr std::string_view kPanelIds[] = {"technique", "filter", "lights", "camera", "views", "timings", "tools"};

// Upper bound on `wait`: 10 minutes at 60 fps; longer is a typo, not a plan.
constexpr int kMaxWaitFrames = 36000;
// Fastest `play`: beyond it a 4 s animation passes in a frame or two.
constexpr float kMaxPlaySpeed = 16.0f;
// The longest `light` action: set N KEY X Y Z.
constexpr size_t kMaxLightArgs = 6;

constexpr Verb kVerbs[] = {
    {"scene", 1, 1, "NAME|FILE", "load a built-in scene or a scene file (the technique stays)"},
    {"filter", 1, 1, "ID", "switch the filter (refused pairs are reported and leave it unchanged)"},
    {"projection", 1, 1, "ID", "switch the projection"},
    {"set", 1, 1, "KEY=VALUE", "set a parameter (technique or scene), as --set does"},
    {"camera", 2, 7, "orbit YAW PITCH DIST | look PX PY PZ TX TY TZ | mode orbit|fly",
     "place the camera (degrees, metres; orbit is around the current target)"},
    {"light", 1, kMaxLightArgs,
     "select N | add sun|spot|point | remove N | set N KEY VALUE | angles AZIMUTH ELEVATION | direction X Y Z | "
     "position X Y Z",
     "lights, numbered from 0: select one (what the debug views show and the other actions move), add one (and select "
     "it; placed where the view shows it), remove one, set one's KEY (the scene file's: type, position, direction, "
     "target, size, color, intensity, outerConeDeg, innerConeDeg, range, castsShadow on|off, mapSize; vectors as X Y Z "
     "or X,Y,Z), or move the selected one (degrees; angles as seen from the point it lights)"},
    {"view", 1, 1, "NAME", "main view: shaded, heatmap, reference, or a debug image (visibility, shadow-map, moments, ...)"},
    {"inset", 1, 1, "NAME|none", "debug image shown in the corner of the view (kept across filter switches)"},
    {"flip", 0, 0, "", "as the R key: technique <-> reference (the heatmap is traced first if needed)"},
    {"split", 1, 2, "FILTER [PROJECTION] | off", "split view: the right half shows that technique (projection: the current)"},
    {"panel", 1, 1, "technique|filter|lights|camera|views|timings|tools", "open that panel's tab"},
    {"time", 1, 1, "SECONDS", "pose the animated scene at this time (clamped to its length) and pause"},
    {"play", 0, 1, "[SPEED]", "play the animation from the current time, SPEED x real time (default 1; scripted: 1/30 s per frame)"},
    {"pause", 0, 0, "", "stop the animation where it is"},
    {"wait", 1, 1, "FRAMES", "let frames pass"},
    {"screenshot", 1, 1, "PATH", "after this frame, write the 3D view (no panels) as PNG"},
    {"screenshot-window", 1, 1, "PATH", "after this frame, write the whole window (with panels) as PNG"},
    {"screenshot-inset", 1, 1, "PATH", "after this frame, write the inset (with its labels) as PNG"},
    {"print", 1, 1, "gl-objects|technique|params|timings|lights|layout|time",
     "print a line on stdout (params: the technique's parameters as key=value; layout: the open panel's extent)"},
    {"heatmap", 0, 1, "[SAMPLES]", "start the error heatmap against the ray-traced reference"},
    {"wait-heatmap", 0, 0, "", "let frames pass until the heatmap is done"},
    {"reload", 0, 0, "", "reload shaders from the source tree (errors are printed)"},
    {"wait-reload", 0, 0, "",
     "let frames pass until a saved file is reloaded (a shader, a technique folder's GLSL or technique.json; at most 60 s)"},
    {"save", 1, 1, "PATH", "save the current scene, camera, light and technique as a scene file"},
    {"ui", 1, 1, "on|off", "show or hide the panels"},
    {"quit", 0, 0, "", "stop here"},
};

const Verb* findVerb(std::string_view name) {
  for (const Verb& v : kVerbs)
    if (v.name == name) return &v;
  return nullptr;
}

[[noreturn]] void fail(const ScriptAction& a, const std::string& what) {
  throw usageError(fmt::format("{}: {}: {}", a.where, a.verb, what));
}

void checkLightAction(const ScriptAction& a, const Verb& v) {
  const std::string& sub = a.args[0];
  const int maxIndex = static_cast<int>(kMaxShadowedLights) - 1;
  if (sub == "set") {
    if (a.args.size() < 4) fail(a, "expected light set N KEY VALUE");
    scriptInt(a, 1, 0, maxIndex);
    try {
      checkLightSetting(a.args[2], std::span(a.args).subspan(3));
    } catch (const Error& e) {
      fail(a, e.what());
    }
    return;
  }
  const size_t n = (sub == "select" || sub == "add" || sub == "remove") ? 2 : sub == "angles" ? 3
                 : (sub == "direction" || sub == "position") ? 4 : 0;
  if (n == 0 || a.args.size() != n) fail(a, fmt::format("expected light {}", v.usage));
  if (sub == "select" || sub == "remove") scriptInt(a, 1, 0, maxIndex);
  if (sub == "add") {
    try {
      parseLightType(a.args[1]);
    } catch (const Error& e) {
      fail(a, e.what());
    }
  }
  if (sub == "angles" || sub == "direction" || sub == "position")
    for (size_t i = 1; i < n; ++i) scriptFloat(a, i);
}

void checkAction(const ScriptAction& a) {
  const Verb* v = findVerb(a.verb);
  if (!v) {
    std::string known;
    for (const Verb& k : kVerbs) known += (known.empty() ? "" : ", ") + std::string(k.name);
    throw usageError(fmt::format("{}: unknown action '{}' (known: {})", a.where, a.verb, known));
  }
  if (a.args.size() < v->minArgs || a.args.size() > v->maxArgs)
    fail(a, fmt::format("expected {} {}", a.verb, v->usage));
  const std::string sub = a.args.empty() ? "" : a.args[0];
  if (a.verb == "set" && a.args[0].find('=') == std::string::npos) fail(a, "expected KEY=VALUE");
  if (a.verb == "wait") scriptInt(a, 0, 0, kMaxWaitFrames);
  if (a.verb == "heatmap" && !a.args.empty()) scriptInt(a, 0, 1, 1 << 16);
  if (a.verb == "ui" && sub != "on" && sub != "off") fail(a, "expected on or off");
  if (a.verb == "print" && sub != "gl-objects" && sub != "technique" && sub != "params" && sub != "timings" && sub != "lights" &&
      sub != "layout" && sub != "time")
    fail(a, "expected gl-objects, technique, params, timings, lights, layout or time");
  if (a.verb == "time" && scriptFloat(a, 0) < 0.0f) fail(a, "expected a time of at least 0 s");
  if (a.verb == "play" && !a.args.empty() && !(scriptFloat(a, 0) > 0.0f && scriptFloat(a, 0) <= kMaxPlaySpeed))
    fail(a, fmt::format("expected a speed above 0 and at most {}", kMaxPlaySpeed));
  if (a.verb == "panel" && std::none_of(std::begin(kPanelIds), std::end(kPanelIds), [&](std::string_view p) { return p == sub; }))
    fail(a, "expected technique, filter, lights, camera, views, timings or tools");
  if (a.verb == "split" && sub == "off" && a.args.size() != 1) fail(a, "expected split off");
  if (a.verb == "camera") {
    const size_t n = sub == "orbit" ? 4 : sub == "look" ? 7 : sub == "mode" ? 2 : 0;
    if (n == 0 || a.args.size() != n) fail(a, fmt::format("expected camera {}", v->usage));
    if (sub == "mode" && a.args[1] != "orbit" && a.args[1] != "fly") fail(a, "expected mode orbit or fly");
    for (size_t i = 1; sub != "mode" && i < n; ++i) scriptFloat(a, i);
  }
  if (a.verb == "light") checkLightAction(a, *v);
}

}  // namespace

int scriptInt(const ScriptAction& a, size_t index, int min, int max) {
  const std::string& s = a.args.at(index);
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || v < min || v > max)
    fail(a, fmt::format("'{}' is not a whole number in {}..{}", s, min, max));
  return v;
}

float scriptFloat(const ScriptAction& a, size_t index) {
  const std::string& s = a.args.at(index);
  float v = 0.0f;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) fail(a, fmt::format("'{}' is not a number", s));
  return v;
}

std::vector<ScriptAction> parseScript(std::string_view text, const std::string& fileName) {
  std::vector<ScriptAction> out;
  std::istringstream in{std::string(text)};
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    ScriptAction a;
    if (!(words >> a.verb)) continue;
    for (std::string w; words >> w;) a.args.push_back(w);
    a.line = n;
    a.where = fmt::format("{}:{}", fileName, n);
    checkAction(a);
    out.push_back(std::move(a));
  }
  return out;
}

std::vector<ScriptAction> loadScript(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw usageError(fmt::format("--script {}: cannot open the file", path.string()));
  const std::string text(std::istreambuf_iterator<char>(f), {});
  return parseScript(text, path.string());
}

std::string scriptHelp() {
  std::string out;
  for (const Verb& v : kVerbs)
    out += fmt::format("  {}{}{}\n      {}\n", v.name, v.usage.empty() ? "" : " ", v.usage, v.help);
  return out;
}

}  // namespace penumbra::viewer
