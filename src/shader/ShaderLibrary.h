#pragma once
// The shader library: .glsl sources embedded in the binary at build time (so the program runs
// from any directory), optionally re-read from the source tree (the viewer's hot reload).
// Our own `#include "key"` expansion (missing files and recursion are errors; `#pragma once` is
// honoured) emits `#line` directives so that driver logs map back to `file.glsl:line`.
#include "gl/Objects.h"

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <tuple>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// Compile-time variants: a generated `#define NAME VALUE` prelude.
class ShaderDefines {
public:
  ShaderDefines& set(std::string name, std::string value = "1");
  ShaderDefines& set(std::string name, int value) { return set(std::move(name), std::to_string(value)); }
  std::string prelude() const;
  bool operator<(const ShaderDefines& o) const { return mItems < o.mItems; }
  ShaderDefines& merge(const ShaderDefines& o);

private:
  std::map<std::string, std::string> mItems;
};

struct ExpandedSource {
  std::string text;                ///< no #version line; starts with `#line 1 0`
  std::vector<std::string> files;  ///< source-string number → file key
};

using SourceReader = std::function<std::optional<std::string>(std::string_view key)>;

/// Expands `#include "key"` recursively, starting from `rootKeys` in order. Throws Error naming
/// the including file and line for a missing file or an include cycle.
ExpandedSource expandIncludes(const std::vector<std::string>& rootKeys, const SourceReader& read);

/// Rewrites driver log lines "N:L(C): …" (Mesa) and "N(L) : …" (NVIDIA) as "file.glsl:L: …".
std::string remapShaderLog(std::string_view log, const std::vector<std::string>& files);

/// One program: each stage is a list of source keys compiled as one (e.g. a filter's file and
/// the visibility pass's main).
struct ProgramDesc {
  std::string label;
  std::vector<std::string> compute, vertex, fragment;
  ShaderDefines defines;
  auto key() const { return std::tie(compute, vertex, fragment, defines); }
  bool operator<(const ProgramDesc& o) const { return key() < o.key(); }
};

class ShaderLibrary {
public:
  ShaderLibrary();
  /// Reads sources from this tree (its shaders/ and src/) before the embedded copies.
  void setSourceTree(std::filesystem::path root) { mSourceTree = std::move(root); }
  /// A key's text: an absolute path is read from that file (a technique folder's GLSL), any
  /// other key from the source tree, then the embedded copies.
  std::optional<std::string> source(std::string_view key) const;
  std::vector<std::string> keys() const;

  /// Compiles (or returns the cached) program. Throws Error with the log mapped to file:line.
  const gl::Program& program(const ProgramDesc& desc);
  /// Recompiles every cached program from current sources; a program that fails keeps its last
  /// good version. Returns the error messages (empty = all compiled).
  std::vector<std::string> reloadAll();
  size_t cachedPrograms() const { return mCache.size(); }

private:
  gl::Program build(const ProgramDesc& desc) const;
  std::optional<std::filesystem::path> mSourceTree;
  std::map<ProgramDesc, gl::Program> mCache;
};

}  // namespace penumbra
