#include "techniques/folder/FolderTechnique.h"

#include "frame/FrameContext.h"
#include "frame/MinDepthPyramid.h"
#include "frame/MipBuilder.h"
#include "frame/SatBuilder.h"
#include "frame/ShadowMaps.h"
#include "techniques/filters/PcfFilter.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

namespace penumbra {
namespace {

using nlohmann::json;

constexpr std::string_view kDescriptionFile = "technique.json";
constexpr std::string_view kDefaultVisibilityFile = "visibility.glsl";
// The names "maps" may hold, in the order docs/own-technique.md lists them.
constexpr std::string_view kMapNames[] = {"depth", "moments", "moments4", "mips", "sat", "min-depth"};
// The most parameters a folder may declare: its uniform block holds them as floats in vec4s.
constexpr size_t kMaxParams = 64;

/// Reads one description, throwing usage Errors that name the file and the field.
class Reader {
public:
  explicit Reader(std::string file) : mFile(std::move(file)) {}

  [[noreturn]] void fail(std::string_view field, std::string_view what) const {
    throw usageError(fmt::format("{}: {}: {}", mFile, field, what));
  }

  const json& need(const json& object, std::string_view field, std::string_view path) const {
    const auto it = object.find(std::string(field));
    if (it == object.end()) fail(path, "missing");
    return *it;
  }

  std::string string(const json& v, std::string_view path, bool nonEmpty = true) const {
    if (!v.is_string()) fail(path, fmt::format("expected a string, found {}", v.dump()));
    std::string s = v.get<std::string>();
    if (nonEmpty && s.empty()) fail(path, "must not be empty");
    return s;
  }

  float number(const json& v, std::string_view path) const {
    if (!v.is_number()) fail(path, fmt::format("expected a number, found {}", v.dump()));
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > 1e30) fail(path, fmt::format("{} is not a finite float", v.dump()));
    return static_cast<float>(d);
  }

  void onlyFields(const json& object, std::span<const std::string_view> known, std::string_view path) const {
    for (const auto& [name, value] : object.items())
      if (std::find(known.begin(), known.end(), name) == known.end())
        fail(path.empty() ? name : fmt::format("{}.{}", path, name),
             fmt::format("unknown field (known: {})", joinNames(known)));
  }

private:
  std::string mFile;
};

bool isIdentifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

bool isTechniqueId(std::string_view s) {
  if (s.empty() || !std::islower(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '-';
  });
}

FolderMaps readMaps(const Reader& r, const json& maps) {
  if (!maps.is_array() || maps.empty())
    r.fail("maps", fmt::format("expected a list of maps from {}, found {}", joinNames(kMapNames), maps.dump()));
  FolderMaps out;
  std::set<std::string> seen;
  for (size_t i = 0; i < maps.size(); ++i) {
    const std::string path = fmt::format("maps[{}]", i);
    const std::string name = r.string(maps[i], path);
    if (std::find(std::begin(kMapNames), std::end(kMapNames), name) == std::end(kMapNames))
      r.fail(path, fmt::format("unknown map '{}' (known: {})", name, joinNames(kMapNames)));
    if (!seen.insert(name).second) r.fail(path, fmt::format("'{}' is listed twice", name));
    if (name == "moments" || name == "moments4") {
      if (out.moments != 0) r.fail(path, "a technique stores one set of moments: 'moments' (z, z²) or 'moments4' (z … z⁴)");
      out.moments = name == "moments" ? 2 : 4;
    }
    out.mips = out.mips || name == "mips";
    out.sat = out.sat || name == "sat";
    out.minDepth = out.minDepth || name == "min-depth";
  }
  if (out.mips && out.moments == 0) r.fail("maps", "'mips' filters the moments: list 'moments' or 'moments4' with it");
  return out;
}

void readParam(const Reader& r, const json& p, size_t index, const std::string& id, FolderDescription::Param& out, ParamDesc& desc,
               std::set<std::string>& names) {
  const std::string path = fmt::format("params[{}]", index);
  if (!p.is_object()) r.fail(path, fmt::format("expected an object, found {}", p.dump()));
  constexpr std::string_view kFields[] = {"name", "label", "meaning", "unit", "default", "range", "choices", "integer", "constant"};
  r.onlyFields(p, kFields, path);
  const std::string name = r.string(r.need(p, "name", path + ".name"), path + ".name");
  if (!isIdentifier(name)) r.fail(path + ".name", fmt::format("'{}' is not a GLSL identifier (a letter, then letters, digits or _)", name));
  if (!names.insert(name).second) r.fail(path + ".name", fmt::format("'{}' is declared twice", name));
  out.key = id + "." + name;
  out.label = p.contains("label") ? r.string(p["label"], path + ".label") : name;
  out.help = r.string(r.need(p, "meaning", path + ".meaning"), path + ".meaning");
  const bool constant = p.contains("constant") && (p["constant"].is_boolean() ? p["constant"].get<bool>()
                                                                               : (r.fail(path + ".constant", "expected true or false"), false));
  if (p.contains("integer") && !p["integer"].is_boolean()) r.fail(path + ".integer", "expected true or false");
  const bool integer = p.value("integer", false);
  if (constant) out.define = "PARAM_" + name;

  const json& def = r.need(p, "default", path + ".default");
  if (p.contains("choices")) {
    if (p.contains("range")) r.fail(path + ".range", "a parameter has choices or a range, not both");
    if (p.contains("unit")) r.fail(path + ".unit", "a choice has no unit");
    const json& choices = p["choices"];
    if (!choices.is_array() || choices.size() < 2) r.fail(path + ".choices", "expected a list of at least two names");
    for (size_t c = 0; c < choices.size(); ++c) {
      const std::string cp = fmt::format("{}.choices[{}]", path, c);
      const std::string choice = r.string(choices[c], cp);
      if (!isIdentifier(choice)) r.fail(cp, fmt::format("'{}' is not an identifier (letters, digits, _)", choice));
      if (std::find(out.choiceNames.begin(), out.choiceNames.end(), choice) != out.choiceNames.end())
        r.fail(cp, fmt::format("'{}' is listed twice", choice));
      out.choiceNames.push_back(choice);
    }
    for (const std::string& c : out.choiceNames) out.choices.emplace_back(c);
    const std::string chosen = r.string(def, path + ".default");
    const auto it = std::find(out.choiceNames.begin(), out.choiceNames.end(), chosen);
    if (it == out.choiceNames.end()) r.fail(path + ".default", fmt::format("'{}' is not one of the choices ({})", chosen, joinNames(out.choiceNames)));
    desc = ParamDesc{out.key, out.label, out.help, {}, static_cast<float>(it - out.choiceNames.begin()), 0.0f,
                     static_cast<float>(out.choiceNames.size() - 1), 1.0f, out.choices, out.define};
    return;
  }
  out.unit = r.string(r.need(p, "unit", path + ".unit"), path + ".unit", false);
  const json& range = r.need(p, "range", path + ".range");
  if (!range.is_array() || range.size() != 2) r.fail(path + ".range", fmt::format("expected [min, max], found {}", range.dump()));
  const float lo = r.number(range[0], path + ".range[0]"), hi = r.number(range[1], path + ".range[1]");
  if (!(lo < hi)) r.fail(path + ".range", fmt::format("min {} must be below max {}", lo, hi));
  const float value = r.number(def, path + ".default");
  if (value < lo || value > hi) r.fail(path + ".default", fmt::format("{} lies outside the range [{}, {}]", value, lo, hi));
  if (integer && (lo != std::floor(lo) || hi != std::floor(hi) || value != std::floor(value)))
    r.fail(path + ".default", "an integer parameter's default and range are whole numbers");
  if (constant && !integer) r.fail(path + ".constant", "a compile-time constant is an integer or a choice: add \"integer\": true");
  desc = ParamDesc{out.key, out.label, out.help, out.unit, value, lo, hi, integer ? 1.0f : 0.0f, {}, out.define};
}

void addGlslConstants(FolderDescription& d) {
  auto& c = d.glslConstants;
  d.runtimeSlots.assign(d.params.size(), -1);
  for (size_t i = 0; i < d.params.size(); ++i) {
    const FolderDescription::Param& p = d.params[i];
    const std::string name = p.key.substr(d.id.size() + 1);
    for (size_t k = 0; k < p.choiceNames.size(); ++k) c.emplace_back(fmt::format("PARAM_{}_{}", name, p.choiceNames[k]), std::to_string(k));
    if (!p.define.empty()) continue;  // its value is the constant PARAM_<name> (Parameterized::compileTimeConstants)
    const int slot = d.runtimeCount++;
    d.runtimeSlots[i] = slot;
    constexpr std::string_view kLanes = "xyzw";
    const std::string read = fmt::format("pn_techniqueParams[{}].{}", slot / 4, kLanes[static_cast<size_t>(slot % 4)]);
    // Choices and integers read as ints, as built-in filters read their modes.
    c.emplace_back("PARAM_" + name, p.choiceNames.empty() && d.descs[i].step != 1.0f ? read : fmt::format("int({})", read));
  }
  c.emplace_back("PN_TECHNIQUE_PARAM_VEC4S", std::to_string(std::max(1, (d.runtimeCount + 3) / 4)));
  if (d.maps.moments) c.emplace_back("PN_TECHNIQUE_MOMENTS", std::to_string(d.maps.moments));
  if (d.maps.sat) c.emplace_back("PN_TECHNIQUE_SAT", "1");
  if (d.maps.minDepth) c.emplace_back("PN_TECHNIQUE_MIN_DEPTH", "1");
}

class FolderFilter final : public Filter {
public:
  explicit FolderFilter(const FolderDescription& d) : Filter(d.descs), mDesc(d) {}
  std::string_view id() const override { return mDesc.id; }
  std::string_view description() const override { return mDesc.description; }

  void renderShadowMaps(FrameContext& frame) override {
    const FolderMaps& m = mDesc.maps;
    if (m.moments == 0) {
      mMaps.ensure(mDesc.id + " shadow map", frame.mapSize(), frame.viewCount());
      frame.renderViews(mMaps, frame.shadowProgram());
      return;
    }
    constexpr int kFullMipChain = 0;
    mMaps.ensure(mDesc.id + " moments", frame.mapSize(), frame.viewCount(), m.moments == 2 ? GL_RG32F : GL_RGBA32F,
                 m.mips ? kFullMipChain : 1);
    ShaderDefines defines = ShaderDefines().set("PN_MOMENT_COUNT", m.moments);
    if (m.moments == 2) defines.set("PN_MOMENT_SLOPE_VARIANCE");
    // Cleared to the moments of the far plane (z = 1): no occluder where nothing was drawn.
    frame.renderViews(mMaps, frame.shadowProgram("passes/moments.frag.glsl", defines), glm::vec4(1.0f));
  }

  void prefilter(FrameContext& frame) override {
    const FolderMaps& m = mDesc.maps;
    if (m.mips) MipBuilder::build(mMaps.color());
    if (m.sat) mSat.build(frame.shaders(), mMaps.depth(), m.moments == 4 ? 4 : 2);
    if (m.minDepth) mPyramid.build(frame.shaders(), mMaps.depth());
  }

  void computeVisibility(FrameContext& frame) override {
    std::vector<glm::vec4> block(static_cast<size_t>(std::max(1, (mDesc.runtimeCount + 3) / 4)), glm::vec4(0.0f));
    for (size_t i = 0; i < mDesc.params.size(); ++i)
      if (const int slot = mDesc.runtimeSlots[i]; slot >= 0)
        block[static_cast<size_t>(slot / 4)][slot % 4] = frame.param(mDesc.params[i].key);
    frame.setFilterBlockBytes(block.data(), block.size() * sizeof(glm::vec4));
    const FolderMaps& m = mDesc.maps;
    mMaps.depth().bindUnit(PN_TEX_FILTER0);
    mMaps.depth().bindUnit(PN_TEX_FILTER1);
    mCompare.bind(PN_TEX_FILTER1);
    if (m.minDepth) mPyramid.pyramid().bindUnit(PN_TEX_MIN_DEPTH);
    if (m.moments) {
      if (m.mips) MipBuilder::setTrilinear(mMaps.color());
      mMaps.color().bindUnit(PN_TEX_FILTER3);
    }
    if (m.sat) mSat.bindTable();
    ShaderDefines defines;
    for (const auto& [name, value] : mDesc.glslConstants) defines.set(name, value);
    const gl::Program* program = nullptr;
    try {
      program = &frame.visibilityProgram(mDesc.visibilityFile.string(), defines);
    } catch (const Error& e) {
      ComparisonSampler::unbind(PN_TEX_FILTER1);
      // The user's GLSL is input: its errors are usage errors, on one line, at the user's file:line.
      std::string message = e.what();
      if (const size_t colon = message.find(":\n"); colon != std::string::npos) message = message.substr(colon + 2);
      for (size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at)) message.replace(at, 1, "; ");
      throw usageError(fmt::format("technique folder {}: {}", mDesc.folder.string(), message));
    }
    frame.dispatchScreen(*program);
    ComparisonSampler::unbind(PN_TEX_FILTER1);
  }

  std::vector<DebugImage> debugImages() const override {
    std::vector<DebugImage> out = {{std::string(kShadowMapImage), &mMaps.depth(), kShadowMapMeaning}};
    if (mDesc.maps.moments) out.push_back({std::string(kMomentsImage), &mMaps.color(), "moments (z, z², …) of the linear light depth z"});
    if (mDesc.maps.minDepth) out.push_back({"min-depth", &mPyramid.pyramid(), "nearest linear light depth over 2×2 texels (level 0)"});
    return out;
  }

private:
  const FolderDescription& mDesc;
  ShadowMapArray mMaps;
  ComparisonSampler mCompare;
  SatBuilder mSat;
  MinDepthPyramid mPyramid;
};

}  // namespace

std::unique_ptr<FolderDescription> readFolderDescription(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw usageError(fmt::format("technique folder {}: not a folder", folder.string()));
  const std::filesystem::path file = folder / kDescriptionFile;
  std::ifstream in(file, std::ios::binary);
  if (!in) throw usageError(fmt::format("technique folder {}: no {} in it", folder.string(), kDescriptionFile));
  const Reader r(file.string());
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw usageError(fmt::format("{}: not JSON ({})", file.string(), e.what()));
  }
  if (!j.is_object()) r.fail("(top level)", "expected an object");
  constexpr std::string_view kFields[] = {"id", "description", "visibility", "maps", "params"};
  r.onlyFields(j, kFields, "");

  auto d = std::make_unique<FolderDescription>();
  d->folder = std::filesystem::weakly_canonical(std::filesystem::absolute(folder));
  d->descriptionFile = d->folder / kDescriptionFile;
  d->id = r.string(r.need(j, "id", "id"), "id");
  if (!isTechniqueId(d->id)) r.fail("id", fmt::format("'{}' is not an id: lower-case letters, digits and '-', starting with a letter", d->id));
  d->description = r.string(r.need(j, "description", "description"), "description");
  const std::string visibility = j.contains("visibility") ? r.string(j["visibility"], "visibility") : std::string(kDefaultVisibilityFile);
  d->visibilityFile = d->folder / visibility;
  if (!std::filesystem::is_regular_file(d->visibilityFile, ec))
    r.fail("visibility", fmt::format("{} does not exist", d->visibilityFile.string()));
  d->maps = readMaps(r, r.need(j, "maps", "maps"));

  const json params = j.contains("params") ? j["params"] : json::array();
  if (!params.is_array()) r.fail("params", "expected a list of parameters");
  if (params.size() > kMaxParams) r.fail("params", fmt::format("{} parameters; at most {}", params.size(), kMaxParams));
  d->params.resize(params.size());
  d->descs.resize(params.size());
  std::set<std::string> names;
  for (size_t i = 0; i < params.size(); ++i) readParam(r, params[i], i, d->id, d->params[i], d->descs[i], names);
  addGlslConstants(*d);
  return d;
}

std::unique_ptr<Filter> makeFolderFilter(const FolderDescription& description) { return std::make_unique<FolderFilter>(description); }

}  // namespace penumbra
