#pragma once
// Parameters are declared once, as ParamDesc tables, and reach the CLI (--set key=value), scene
// files ("params"), the viewer's widgets and benchmark sweeps from that one table.
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

/// The kinds of light a parameter acts on (ParamDesc::lights), as bits: a parameter that only
/// shapes a point light's cube cannot change a frame lit by suns and spots, so `tune` does not
/// search it there.
inline constexpr unsigned kSunLightBit = 1u, kSpotLightBit = 2u, kPointLightBit = 4u;
inline constexpr unsigned kAnyLightBits = kSunLightBit | kSpotLightBit | kPointLightBit;

/// One tunable. Numeric unless `choices` is non-empty, in which case the value is the index of
/// the chosen name (def/min/max are indices too). Its unit is `unit`, and part of the key where
/// it fits ("…Texels", "…M").
struct ParamDesc {
  std::string_view key;    ///< "technique.name", e.g. "pcss.blockerSamples"
  std::string_view label;  ///< short UI label
  std::string_view help;   ///< one sentence: meaning, unit
  /// The unit of a numeric value, shown beside it (viewer sliders, penumbra list): "texels",
  /// "m", "texels²", "depth range" (a fraction of the map's depth range), "factor" or "fraction"
  /// for dimensionless ones, "m | rad" where the light's kind decides. Empty for choices.
  std::string_view unit;
  float def = 0.0f, min = 0.0f, max = 1.0f, step = 0.0f;  ///< step 1 = integer-valued
  std::span<const std::string_view> choices = {};
  /// The GLSL constant that carries the value into the filter's program (integer-valued
  /// parameters that shape its code: modes, kernels, tap counts), e.g. "PN_PCF_SAMPLES": the
  /// program is built per value (FrameContext::visibilityProgram) and its loops and branches
  /// fold. Empty: the value reaches the shader through the filter's uniform block.
  std::string_view define = {};
  /// The kinds of light it acts on (kSunLightBit, …); kAnyLightBits for most.
  unsigned lights = kAnyLightBits;

  bool isChoice() const { return !choices.empty(); }
  bool isInteger() const { return isChoice() || step == 1.0f; }
};

/// The choice names of an off/on parameter (e.g. pcf.hardwareCompare), in value order.
inline constexpr std::string_view kOffOn[] = {"off", "on"};

/// Parses `text` for `desc` (a number, or a choice name); throws a usage Error naming the key
/// when the text is not a number/choice or lies outside [min, max].
float parseParamValue(const ParamDesc& desc, std::string_view text);
/// Checks a numeric value against the range; throws a usage Error naming the key.
void checkParamValue(const ParamDesc& desc, float value);
/// "0.002", "slope", "16".
std::string formatParamValue(const ParamDesc& desc, float value);
/// Splits "key=value"; throws a usage Error if there is no '='.
std::pair<std::string, std::string> splitAssignment(std::string_view text);

/// The current values of one ParamDesc table: a technique's projection, filter and add-on values
/// (penumbra/Technique.h), and the base of every projection (a light's instance is its values).
class Parameterized {
public:
  explicit Parameterized(std::span<const ParamDesc> descs);
  virtual ~Parameterized() = default;

  std::span<const ParamDesc> paramDescs() const { return mDescs; }
  bool hasParam(std::string_view key) const;
  /// Throws a usage Error for an unknown key or an out-of-range value.
  void setParam(std::string_view key, float value);
  void setParam(std::string_view key, std::string_view text);
  float param(std::string_view key) const;
  int paramInt(std::string_view key) const { return static_cast<int>(param(key)); }
  /// (define, value) of every parameter that declares a GLSL constant (ParamDesc::define).
  std::vector<std::pair<std::string_view, int>> compileTimeConstants() const;
  /// The same table with the same values.
  bool sameValues(const Parameterized& other) const {
    return mDescs.data() == other.mDescs.data() && mDescs.size() == other.mDescs.size() && mValues == other.mValues;
  }

private:
  size_t indexOf(std::string_view key) const;
  std::span<const ParamDesc> mDescs;
  std::vector<float> mValues;
};

/// "a, b, c": names joined for messages and listings.
template <class Range>
std::string joinNames(const Range& names, std::string_view separator = ", ") {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += separator;
    out += std::string_view(n);
  }
  return out;
}

/// Scene-level parameters ("light.size", ...): they change the scene, not a technique.
std::span<const ParamDesc> sceneParamDescs();
/// The scene parameter `key` (one of sceneParamDescs()); throws a usage Error for another key.
const ParamDesc& sceneParamDesc(std::string_view key);

}  // namespace penumbra
