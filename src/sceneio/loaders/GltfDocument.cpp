// glTF JSON checks before tinygltf (GltfDocument.h).
#include "sceneio/loaders/GltfDocument.h"

#include "sceneio/JsonProblem.h"
#include "sceneio/loaders/ModelImport.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::loaders {
namespace {

using Json = nlohmann::json;

// Deepest nesting of arrays/objects, by a scan that skips strings: no recursion, any input.
int jsonDepth(std::span<const uint8_t> text) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const uint8_t c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

/// What a member must be.
enum class Kind { Index, Count, String, Object, Array, Number };

const char* kindText(Kind k) {
  switch (k) {
    case Kind::Index: return "a non-negative integer (an index)";
    case Kind::Count: return "a non-negative integer";
    case Kind::String: return "a string";
    case Kind::Object: return "an object";
    case Kind::Array: return "an array";
    default: return "a number";
  }
}

bool is(const Json& v, Kind k) {
  switch (k) {
    case Kind::Index: case Kind::Count: return v.is_number_unsigned();
    case Kind::String: return v.is_string();
    case Kind::Object: return v.is_object();
    case Kind::Array: return v.is_array();
    default: return v.is_number();
  }
}

struct Member {
  const char* key;
  Kind kind;
};

class Checker {
public:
  explicit Checker(std::string file) : mFile(std::move(file)) {}

  /// `o[key]` must exist (when `required`) and be of `kind`.
  void member(const Json& o, const std::string& field, Member m, bool required = true) const {
    if (!o.contains(m.key)) {
      if (required) fail(mFile, field + "." + m.key, fmt::format("missing (glTF 2.0 requires it: {})", kindText(m.kind)));
      return;
    }
    if (!is(o[m.key], m.kind)) fail(mFile, field + "." + m.key, fmt::format("expected {}", kindText(m.kind)));
  }
  void members(const Json& o, const std::string& field, std::initializer_list<Member> required) const {
    for (const Member& m : required) member(o, field, m);
  }
  /// `doc[name]`, when present, must be an array of objects; calls `each(element, field)`.
  template <class F>
  void array(const Json& doc, const std::string& parent, const char* name, F&& each) const {
    if (!doc.contains(name)) return;
    const std::string field = parent.empty() ? name : parent + "." + name;
    if (!doc[name].is_array()) fail(mFile, field, "expected an array");
    for (size_t i = 0; i < doc[name].size(); ++i) {
      const std::string element = fmt::format("{}[{}]", field, i);
      if (!doc[name][i].is_object()) fail(mFile, element, "expected an object");
      each(doc[name][i], element);
    }
  }
  const std::string& file() const { return mFile; }

private:
  std::string mFile;
};

// glTF 1.0 kept its top-level collections in objects keyed by name; 2.0 uses arrays.
bool looksLikeGltf1(const Json& doc) {
  for (const char* key : {"meshes", "nodes", "accessors", "buffers", "materials"})
    if (doc.contains(key) && doc[key].is_object()) return true;
  return false;
}

void checkVersion(const Checker& c, const Json& doc) {
  const char* const kConvert = "Penumbra reads glTF 2.0 only (convert it first, e.g. with gltf-pipeline, which upgrades 1.0 files)";
  if (!doc.contains("asset")) {
    if (looksLikeGltf1(doc)) fail(c.file(), "", fmt::format("a glTF 1.0 file (no asset, collections keyed by name): {}", kConvert));
    fail(c.file(), "asset", "missing (every glTF 2.0 file has \"asset\": {\"version\": \"2.0\"})");
  }
  c.member(doc, "", {"asset", Kind::Object});
  c.member(doc["asset"], "asset", {"version", Kind::String});
  const std::string version = doc["asset"]["version"].get<std::string>();
  if (version.rfind("1.", 0) == 0 || version == "1") fail(c.file(), "asset.version", fmt::format("'{}': a glTF 1.0 file: {}", version, kConvert));
  if (version.rfind("2.", 0) != 0) fail(c.file(), "asset.version", fmt::format("'{}' is not glTF 2.x", version));
  if (looksLikeGltf1(doc)) fail(c.file(), "", fmt::format("collections keyed by name are glTF 1.0: {}", kConvert));
}

// Every member tinygltf requires, with its type, so that its own messages (which name no field)
// never show for these.
void checkRequiredMembers(const Checker& c, const Json& doc) {
  c.array(doc, "", "buffers", [&](const Json& b, const std::string& f) {
    c.members(b, f, {{"byteLength", Kind::Count}});
    c.member(b, f, {"uri", Kind::String}, false);
  });
  c.array(doc, "", "bufferViews", [&](const Json& v, const std::string& f) {
    c.members(v, f, {{"buffer", Kind::Index}, {"byteLength", Kind::Count}});
    c.member(v, f, {"byteOffset", Kind::Count}, false);
    c.member(v, f, {"byteStride", Kind::Count}, false);
  });
  c.array(doc, "", "accessors", [&](const Json& a, const std::string& f) {
    c.members(a, f, {{"componentType", Kind::Count}, {"count", Kind::Count}, {"type", Kind::String}});
    c.member(a, f, {"bufferView", Kind::Index}, false);
    c.member(a, f, {"byteOffset", Kind::Count}, false);
  });
  c.array(doc, "", "meshes", [&](const Json& m, const std::string& f) {
    c.members(m, f, {{"primitives", Kind::Array}});
    c.array(m, f, "primitives", [&](const Json& p, const std::string& pf) {
      c.members(p, pf, {{"attributes", Kind::Object}});
      for (const auto& [name, index] : p["attributes"].items())
        if (!is(index, Kind::Index)) fail(c.file(), pf + ".attributes." + name, fmt::format("expected {}", kindText(Kind::Index)));
      for (const char* key : {"indices", "material", "mode"}) c.member(p, pf, {key, Kind::Index}, false);
    });
  });
  c.array(doc, "", "images", [&](const Json& im, const std::string& f) {
    if (!im.contains("uri") && !im.contains("bufferView")) fail(c.file(), f, "has neither uri nor bufferView");
    c.member(im, f, {"uri", Kind::String}, false);
    c.member(im, f, {"bufferView", Kind::Index}, false);
  });
  c.array(doc, "", "cameras", [&](const Json& cam, const std::string& f) {
    c.members(cam, f, {{"type", Kind::String}});
    if (cam.contains("perspective")) {
      c.member(cam, f, {"perspective", Kind::Object});
      c.members(cam["perspective"], f + ".perspective", {{"yfov", Kind::Number}, {"znear", Kind::Number}});
    }
    if (cam.contains("orthographic")) {
      c.member(cam, f, {"orthographic", Kind::Object});
      c.members(cam["orthographic"], f + ".orthographic",
                {{"xmag", Kind::Number}, {"ymag", Kind::Number}, {"zfar", Kind::Number}, {"znear", Kind::Number}});
    }
  });
  c.array(doc, "", "animations", [&](const Json& a, const std::string& f) {
    c.members(a, f, {{"channels", Kind::Array}, {"samplers", Kind::Array}});
    c.array(a, f, "channels", [&](const Json& ch, const std::string& cf) {
      c.members(ch, cf, {{"sampler", Kind::Index}, {"target", Kind::Object}});
      c.members(ch["target"], cf + ".target", {{"path", Kind::String}});
    });
    c.array(a, f, "samplers", [&](const Json& s, const std::string& sf) {
      c.members(s, sf, {{"input", Kind::Index}, {"output", Kind::Index}});
    });
  });
  c.array(doc, "", "skins", [&](const Json& s, const std::string& f) { c.members(s, f, {{"joints", Kind::Array}}); });
  for (const char* name : {"materials", "textures", "samplers", "scenes"}) c.array(doc, "", name, [](const Json&, const std::string&) {});
  // A node's light: tinygltf drops an extension that is not an object (the light would vanish).
  c.array(doc, "", "nodes", [&](const Json& n, const std::string& f) {
    if (!n.contains("extensions")) return;
    c.member(n, f, {"extensions", Kind::Object});
    const std::string ef = f + ".extensions";
    if (!n["extensions"].contains("KHR_lights_punctual")) return;
    c.member(n["extensions"], ef, {"KHR_lights_punctual", Kind::Object});
    c.members(n["extensions"]["KHR_lights_punctual"], ef + ".KHR_lights_punctual", {{"light", Kind::Index}});
  });
  // The lights' members: tinygltf keeps its default for a member of the wrong type ("intensity":
  // "bright" would shine at 1). The ranges are GltfConverter's.
  if (doc.contains("extensions") && doc["extensions"].is_object() && doc["extensions"].contains("KHR_lights_punctual")) {
    const Json& lights = doc["extensions"]["KHR_lights_punctual"];
    if (!lights.is_object()) fail(c.file(), "extensions.KHR_lights_punctual", "expected an object");
    c.array(lights, "extensions.KHR_lights_punctual", "lights", [&](const Json& l, const std::string& f) {
      c.members(l, f, {{"type", Kind::String}});
      for (const char* key : {"intensity", "range"}) c.member(l, f, {key, Kind::Number}, false);
      c.member(l, f, {"name", Kind::String}, false);
      if (l.contains("color") && !(l["color"].is_array() && l["color"].size() == 3 &&
                                   std::all_of(l["color"].begin(), l["color"].end(), [](const Json& x) { return x.is_number(); })))
        fail(c.file(), f + ".color", "expected an array of 3 numbers");
      if (!l.contains("spot")) return;
      c.member(l, f, {"spot", Kind::Object});
      for (const char* key : {"innerConeAngle", "outerConeAngle"}) c.member(l["spot"], f + ".spot", {key, Kind::Number}, false);
    });
  }
}

// tinygltf hands an image from a buffer view to the image callback before any check of ours:
// views must lie inside their buffers before it runs.
void checkViewsInsideBuffers(const Checker& c, const Json& doc) {
  if (!doc.contains("bufferViews")) return;
  const Json empty = Json::array();
  const Json& buffers = doc.contains("buffers") ? doc["buffers"] : empty;
  const Json& views = doc["bufferViews"];
  for (size_t i = 0; i < views.size(); ++i) {
    const Json& v = views[i];
    const std::string field = fmt::format("bufferViews[{}]", i);
    const uint64_t buffer = v["buffer"].get<uint64_t>(), length = v["byteLength"].get<uint64_t>();
    const uint64_t offset = v.contains("byteOffset") ? v["byteOffset"].get<uint64_t>() : 0;
    if (buffer >= buffers.size()) fail(c.file(), field + ".buffer", fmt::format("no buffer {} ({} buffers)", buffer, buffers.size()));
    const uint64_t bufferLength = buffers[buffer]["byteLength"].get<uint64_t>();
    if (offset > bufferLength || length > bufferLength - offset)
      fail(c.file(), field, fmt::format("bytes {}..{} run past the end of buffers[{}] ({} bytes)", offset, offset + length, buffer, bufferLength));
  }
}

}  // namespace

nlohmann::json checkGltfDocument(const std::string& file, std::span<const uint8_t> text) {
  if (jsonDepth(text) > kMaxJsonDepth) fail(file, "", fmt::format("JSON nests deeper than {} levels", kMaxJsonDepth));
  if (const std::string problem = sceneio::jsonParseProblem(text); !problem.empty()) fail(file, "", "not valid JSON: " + problem);
  Json doc = Json::parse(text.begin(), text.end());
  if (!doc.is_object()) fail(file, "", "the glTF document is not a JSON object");
  const Checker c(file);
  checkVersion(c, doc);
  checkRequiredMembers(c, doc);
  checkViewsInsideBuffers(c, doc);
  return doc;
}

}  // namespace penumbra::loaders
