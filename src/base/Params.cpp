#include <penumbra/Error.h>
#include <penumbra/Params.h>

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace penumbra {

void checkParamValue(const ParamDesc& d, float value) {
  if (!std::isfinite(value) || value < d.min || value > d.max)
    throw usageError(fmt::format("{}={} is out of range [{}, {}]", d.key, value, d.min, d.max));
  if (d.isInteger() && value != std::floor(value))
    throw usageError(fmt::format("{}={} must be a whole number", d.key, value));
}

float parseParamValue(const ParamDesc& d, std::string_view text) {
  if (d.isChoice()) {
    for (size_t i = 0; i < d.choices.size(); ++i)
      if (d.choices[i] == text) return static_cast<float>(i);
    const std::string names = joinNames(d.choices);
    throw usageError(fmt::format("{}={}: expected one of {}", d.key, text, names));
  }
  float v = 0.0f;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    throw usageError(fmt::format("{}={}: not a number", d.key, text));
  checkParamValue(d, v);
  return v;
}

std::string formatParamValue(const ParamDesc& d, float value) {
  if (d.isChoice()) {
    const auto i = static_cast<size_t>(value);
    return i < d.choices.size() ? std::string(d.choices[i]) : fmt::format("{}", value);
  }
  return fmt::format("{}", value);
}

std::pair<std::string, std::string> splitAssignment(std::string_view text) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw usageError(fmt::format("'{}': expected key=value", text));
  return {std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
}

Parameterized::Parameterized(std::span<const ParamDesc> descs) : mDescs(descs) {
  for (const ParamDesc& d : descs) mValues.push_back(d.def);
}

bool Parameterized::hasParam(std::string_view key) const {
  for (const ParamDesc& d : mDescs)
    if (d.key == key) return true;
  return false;
}

size_t Parameterized::indexOf(std::string_view key) const {
  for (size_t i = 0; i < mDescs.size(); ++i)
    if (mDescs[i].key == key) return i;
  std::vector<std::string_view> keys;
  for (const ParamDesc& d : mDescs) keys.push_back(d.key);
  throw usageError(fmt::format("unknown parameter '{}' (this one has: {})", key, keys.empty() ? "none" : joinNames(keys)));
}

void Parameterized::setParam(std::string_view key, float value) {
  const size_t i = indexOf(key);
  checkParamValue(mDescs[i], value);
  mValues[i] = value;
}

void Parameterized::setParam(std::string_view key, std::string_view text) {
  const size_t i = indexOf(key);
  mValues[i] = parseParamValue(mDescs[i], text);
}

float Parameterized::param(std::string_view key) const { return mValues[indexOf(key)]; }

std::vector<std::pair<std::string_view, int>> Parameterized::compileTimeConstants() const {
  std::vector<std::pair<std::string_view, int>> out;
  for (size_t i = 0; i < mDescs.size(); ++i) {
    PN_ASSERT(mDescs[i].define.empty() || mDescs[i].isInteger());
    if (!mDescs[i].define.empty()) out.emplace_back(mDescs[i].define, static_cast<int>(mValues[i]));
  }
  return out;
}

namespace {
constexpr ParamDesc kSceneParams[] = {
    {"light.size", "Light size",
     "overrides the first light's size: spot = sphere radius (m), sun = angular radius (rad); 0 = hard; unset = the scene's own size", "m | rad",
     0.0f, 0.0f, 10.0f, 0.0f},
    {"light.count", "Lights used",
     "keeps the scene's first N lights (file order) and drops the rest, e.g. to measure cost per light; 0 = all", "lights",
     0.0f, 0.0f, 16.0f, 1.0f},
};
}  // namespace

std::span<const ParamDesc> sceneParamDescs() { return kSceneParams; }

const ParamDesc& sceneParamDesc(std::string_view key) {
  for (const ParamDesc& d : kSceneParams)
    if (d.key == key) return d;
  throw usageError(fmt::format("unknown scene parameter '{}'", key));
}

}  // namespace penumbra
