// glTF 2.0 input: tinygltf parses the JSON, the GLB container, buffers and data URIs; every
// index, offset, count and number it hands over is checked by GltfConverter.cpp before use,
// because tinygltf checks few of them. Two holes are closed before tinygltf runs: JSON nesting (its `extras`
// reader recurses once per level) and buffer views that run past their buffer (it hands an
// image straight from such a view to the image callback). Images stay encoded until a material
// uses them (GltfTextures.cpp decodes them, size limits first).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE        // GltfTextures.cpp decodes, size limits first
#define TINYGLTF_NO_STB_IMAGE_WRITE  // Penumbra never writes glTF
#include <tiny_gltf.h>

#include "scene/loaders/GltfConverter.h"
#include "scene/loaders/GltfLoader.h"
#include "scene/loaders/GltfTextures.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>

namespace penumbra::loaders {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr size_t kGlbHeaderBytes = 20;          // header (12) + first chunk header (8)

std::string oneLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  for (size_t p = s.find('\n'); p != std::string::npos; p = s.find('\n', p)) s.replace(p, 1, "; ");
  return s.empty() ? "tinygltf reported an unknown error" : s;
}

uint32_t readU32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;  // glTF is little-endian, as every platform Penumbra builds on
}

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

uint64_t unsignedOr(const nlohmann::json& o, const char* key, uint64_t def, bool& ok) {
  if (!o.contains(key)) return def;
  if (!o[key].is_number_unsigned()) { ok = false; return def; }
  return o[key].get<uint64_t>();
}

// Checks made on the raw JSON before tinygltf sees it (see the file comment).
void precheckJson(const std::string& file, std::span<const uint8_t> text) {
  if (jsonDepth(text) > kMaxJsonDepth) fail(file, "", fmt::format("JSON nests deeper than {} levels", kMaxJsonDepth));
  const nlohmann::json doc = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (doc.is_discarded()) fail(file, "", "not valid JSON");
  if (!doc.is_object()) fail(file, "", "the glTF document is not a JSON object");
  if (!doc.contains("bufferViews") || !doc["bufferViews"].is_array()) return;
  const nlohmann::json empty = nlohmann::json::array();
  const nlohmann::json& buffers = doc.contains("buffers") && doc["buffers"].is_array() ? doc["buffers"] : empty;
  const nlohmann::json& views = doc["bufferViews"];
  for (size_t i = 0; i < views.size(); ++i) {
    const nlohmann::json& v = views[i];
    if (!v.is_object()) continue;  // tinygltf rejects it with its own message
    bool ok = true;
    const uint64_t buffer = unsignedOr(v, "buffer", ~uint64_t(0), ok);
    const uint64_t offset = unsignedOr(v, "byteOffset", 0, ok);
    const uint64_t length = unsignedOr(v, "byteLength", 0, ok);
    const std::string field = fmt::format("bufferViews[{}]", i);
    if (!ok) fail(file, field, "buffer, byteOffset and byteLength must be non-negative integers");
    if (buffer >= buffers.size()) fail(file, field + ".buffer", fmt::format("no buffer {} ({} buffers)", buffer, buffers.size()));
    bool okLength = buffers[buffer].is_object();
    const uint64_t bufferLength = okLength ? unsignedOr(buffers[buffer], "byteLength", 0, okLength) : 0;
    if (!okLength) fail(file, fmt::format("buffers[{}].byteLength", buffer), "must be a non-negative integer");
    if (offset > bufferLength || length > bufferLength - offset)
      fail(file, field, fmt::format("bytes {}..{} run past the end of buffers[{}] ({} bytes)", offset, offset + length, buffer, bufferLength));
  }
}

// --- tinygltf callbacks: files with limits ---------------------------------------------------------
bool fileExists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}
std::string expandPath(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    *out = readFileLimited(path, path);
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported";
  return false;
}

// Share of a glTF load spent before the conversion (JSON, buffers, images).
constexpr double kGltfParseShare = 0.4;

}  // namespace

Model loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& name, const std::filesystem::path& baseDir,
                         ProgressReport* progress) {
  if (bytes.empty()) fail(name, "", "the file is empty");
  if (bytes.size() > kMaxFileBytes) fail(name, "", fmt::format("{} bytes, more than the {} byte limit", bytes.size(), kMaxFileBytes));
  const bool binary = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  std::span<const uint8_t> json = bytes;
  if (binary) {
    if (bytes.size() < kGlbHeaderBytes) fail(name, "", fmt::format("truncated GLB: {} bytes, the header needs {}", bytes.size(), kGlbHeaderBytes));
    const uint32_t version = readU32(bytes.data() + 4), length = readU32(bytes.data() + 8);
    const uint32_t jsonLength = readU32(bytes.data() + 12), jsonType = readU32(bytes.data() + 16);
    if (version != 2) fail(name, "", fmt::format("GLB version {} (only 2 is glTF 2.0)", version));
    if (length > bytes.size()) fail(name, "", fmt::format("truncated GLB: the header says {} bytes, the file has {}", length, bytes.size()));
    // Before the subtraction below: a length under the headers' own size would wrap around.
    if (length < kGlbHeaderBytes)
      fail(name, "", fmt::format("malformed GLB: the header says {} bytes, less than its {}-byte headers", length, kGlbHeaderBytes));
    if (jsonType != kGlbJsonChunk || jsonLength > length - kGlbHeaderBytes || jsonLength == 0)
      fail(name, "", "malformed GLB: the first chunk is not a JSON chunk inside the file");
    json = bytes.subspan(kGlbHeaderBytes, jsonLength);
  }
  precheckJson(name, json);

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keepEncodedImage, nullptr);
  loader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  const std::string base = baseDir.empty() ? std::string(".") : baseDir.string();
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base)
                         : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()), size, base);
  if (!ok) fail(name, "", oneLine(err.empty() ? warn : err));
  if (progress) {
    progress->stage(kGltfParseShare, 1.0);
    progress->update(0, 1);
  }
  return convertGltf(model, name, progress);
}

Model loadGltf(const std::filesystem::path& path, ProgressReport& progress) {
  const std::vector<uint8_t> bytes = readFileLimited(path, path.string());
  return loadGltfFromMemory(bytes, path.string(), path.parent_path(), &progress);
}

}  // namespace penumbra::loaders
