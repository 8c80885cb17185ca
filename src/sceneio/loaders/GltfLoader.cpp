// glTF 2.0 input: tinygltf parses the JSON, the GLB container, buffers and data URIs; every
// index, offset, count and number it hands over is checked by GltfConverter.cpp before use,
// because tinygltf checks few of them. GltfDocument.cpp checks the JSON before tinygltf runs
// (nesting, version, required members, views inside buffers), naming the field. Images stay
// encoded until a material uses them (GltfTextures.cpp decodes them, size limits first).
#define TINYGLTF_IMPLEMENTATION  // here, once
#include "sceneio/loaders/TinyGltf.h"

#include "sceneio/loaders/GltfCompression.h"
#include "sceneio/loaders/GltfConverter.h"
#include "sceneio/loaders/GltfDocument.h"
#include "sceneio/loaders/GltfLoader.h"
#include "sceneio/loaders/GltfTextures.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

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

void writeU32(uint8_t* p, uint32_t v) { std::memcpy(p, &v, 4); }

/// The file with its JSON replaced by `text` (a GLB keeps its other chunks as they were).
std::vector<uint8_t> withJson(std::span<const uint8_t> file, bool binary, uint32_t jsonLength, uint32_t length, std::string text,
                              const std::string& name) {
  if (!binary) return {text.begin(), text.end()};
  while (text.size() % 4 != 0) text += ' ';  // chunks stay 4-byte aligned
  const size_t rest = length - kGlbHeaderBytes - jsonLength;  // the chunks after the JSON (checked: inside the file)
  const size_t total = kGlbHeaderBytes + text.size() + rest;
  if (total > UINT32_MAX) fail(name, "", "the GLB would grow past 4 GiB");
  std::vector<uint8_t> out(total);
  writeU32(out.data(), kGlbMagic);
  writeU32(out.data() + 4, 2);
  writeU32(out.data() + 8, static_cast<uint32_t>(total));
  writeU32(out.data() + 12, static_cast<uint32_t>(text.size()));
  writeU32(out.data() + 16, kGlbJsonChunk);
  std::memcpy(out.data() + kGlbHeaderBytes, text.data(), text.size());
  if (rest > 0) std::memcpy(out.data() + kGlbHeaderBytes + text.size(), file.data() + kGlbHeaderBytes + jsonLength, rest);
  return out;
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
  uint32_t length = 0, jsonLength = 0;
  if (binary) {
    if (bytes.size() < kGlbHeaderBytes) fail(name, "", fmt::format("truncated GLB: {} bytes, the header needs {}", bytes.size(), kGlbHeaderBytes));
    const uint32_t version = readU32(bytes.data() + 4), jsonType = readU32(bytes.data() + 16);
    length = readU32(bytes.data() + 8);
    jsonLength = readU32(bytes.data() + 12);
    if (version == 1) fail(name, "", "a binary glTF 1.0 file (GLB version 1): Penumbra reads glTF 2.0 only (convert it first, e.g. with gltf-pipeline, which upgrades 1.0 files)");
    if (version != 2) fail(name, "", fmt::format("GLB version {} (only 2 is glTF 2.0)", version));
    if (length > bytes.size()) fail(name, "", fmt::format("truncated GLB: the header says {} bytes, the file has {}", length, bytes.size()));
    // Before the subtraction below: a length under the headers' own size would wrap around.
    if (length < kGlbHeaderBytes)
      fail(name, "", fmt::format("malformed GLB: the header says {} bytes, less than its {}-byte headers", length, kGlbHeaderBytes));
    if (jsonType != kGlbJsonChunk || jsonLength > length - kGlbHeaderBytes || jsonLength == 0)
      fail(name, "", "malformed GLB: the first chunk is not a JSON chunk inside the file");
    json = bytes.subspan(kGlbHeaderBytes, jsonLength);
  }
  nlohmann::json doc = checkGltfDocument(name, json);
  const CompressedParts compressed = prepareCompressed(doc, name);
  // What tinygltf parses: the file, or the file with the JSON prepared for it.
  const std::vector<uint8_t> prepared = compressed.rewritten ? withJson(bytes, binary, jsonLength, length, doc.dump(), name)
                                                             : std::vector<uint8_t>();
  const std::span<const uint8_t> input = compressed.rewritten ? std::span<const uint8_t>(prepared) : bytes;

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keepEncodedImage, nullptr);
  loader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  const std::string base = baseDir.empty() ? std::string(".") : baseDir.string();
  const auto size = static_cast<unsigned int>(input.size());
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, input.data(), size, base)
                         : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(input.data()), size, base);
  if (!ok) fail(name, "", "glTF parser (tinygltf): " + oneLine(err.empty() ? warn : err));
  decompress(model, compressed, name);
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
