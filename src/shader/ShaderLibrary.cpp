#include "shader/ShaderLibrary.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <fstream>
#include <regex>
#include <set>
#include <span>
#include <sstream>
#include <utility>

namespace penumbra {
namespace detail {
std::span<const std::pair<std::string_view, std::string_view>> embeddedShaderFiles();
}

// ---- defines ----------------------------------------------------------------------------
ShaderDefines& ShaderDefines::set(std::string name, std::string value) {
  mItems[std::move(name)] = std::move(value);
  return *this;
}
ShaderDefines& ShaderDefines::merge(const ShaderDefines& o) {
  for (const auto& [k, v] : o.mItems) mItems[k] = v;
  return *this;
}
std::string ShaderDefines::prelude() const {
  std::string s;
  for (const auto& [k, v] : mItems) s += fmt::format("#define {} {}\n", k, v);
  return s;
}

// ---- include expansion ------------------------------------------------------------------
namespace {

struct Expander {
  const SourceReader& read;
  ExpandedSource out;
  std::vector<std::string> stack;  // keys being expanded, for cycle detection
  std::set<std::string> once;      // files that said #pragma once and were included

  int fileIndex(const std::string& key) {
    for (size_t i = 0; i < out.files.size(); ++i)
      if (out.files[i] == key) return static_cast<int>(i);
    out.files.push_back(key);
    return static_cast<int>(out.files.size() - 1);
  }

  void expand(const std::string& key, const std::string& from, int fromLine) {
    for (const std::string& open : stack)
      if (open == key)
        throw Error(fmt::format("{}:{}: #include \"{}\" is recursive ({} includes itself)", from, fromLine,
                                key, key));
    if (once.count(key)) return;
    const std::optional<std::string> text = read(key);
    if (!text) {
      if (from.empty()) throw Error(fmt::format("shader file \"{}\" not found", key));
      throw Error(fmt::format("{}:{}: #include \"{}\": file not found", from, fromLine, key));
    }
    stack.push_back(key);
    const int index = fileIndex(key);
    out.text += fmt::format("#line 1 {}\n", index);
    std::istringstream in(*text);
    std::string line;
    int lineNo = 0;
    static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*(//.*)?$)");
    static const std::regex onceRe(R"(^\s*#\s*pragma\s+once\s*$)");
    std::smatch m;
    while (std::getline(in, line)) {
      ++lineNo;
      if (std::regex_match(line, m, includeRe)) {
        expand(m[1].str(), key, lineNo);
        out.text += fmt::format("#line {} {}\n", lineNo + 1, index);
      } else if (std::regex_match(line, onceRe)) {
        once.insert(key);
        out.text += "\n";
      } else {
        out.text += line;
        out.text += '\n';
      }
    }
    stack.pop_back();
  }
};

}  // namespace

ExpandedSource expandIncludes(const std::vector<std::string>& rootKeys, const SourceReader& read) {
  Expander e{read, {}, {}, {}};
  for (const std::string& key : rootKeys) e.expand(key, "", 0);
  return std::move(e.out);
}

std::string remapShaderLog(std::string_view log, const std::vector<std::string>& files) {
  static const std::regex mesaRe(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex nvRe(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
  auto name = [&](const std::string& n) {
    const size_t i = std::stoul(n);
    return i < files.size() ? files[i] : "source " + n;
  };
  std::istringstream in{std::string(log)};
  std::string line, out;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, mesaRe))
      out += fmt::format("{}:{}: {}\n", name(m[1]), m[2].str(), m[4].str());
    else if (std::regex_match(line, m, nvRe))
      out += fmt::format("{}:{}: {}\n", name(m[1]), m[2].str(), m[3].str());
    else if (!line.empty())
      out += line + "\n";
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

// ---- library ----------------------------------------------------------------------------
ShaderLibrary::ShaderLibrary() = default;

std::optional<std::string> ShaderLibrary::source(std::string_view key) const {
  // An absolute path is a file of the user's (a technique folder's GLSL): read where it is, every
  // time, so a reload sees its edits; its log lines name that path.
  if (const std::filesystem::path path(key); path.is_absolute()) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return std::nullopt;
    return std::string(std::istreambuf_iterator<char>(f), {});
  }
  if (mSourceTree) {
    for (const char* top : {"shaders", "src"}) {
      std::ifstream f(*mSourceTree / top / std::string(key), std::ios::binary);
      if (f) return std::string(std::istreambuf_iterator<char>(f), {});
    }
  }
  for (const auto& [k, text] : detail::embeddedShaderFiles())
    if (k == key) return std::string(text);
  return std::nullopt;
}

std::vector<std::string> ShaderLibrary::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, text] : detail::embeddedShaderFiles()) out.emplace_back(k);
  return out;
}

namespace {

// A shader object lives only until its program is linked, so it is not a gl:: wrapper counted by
// gl::liveObjectCount; this guard deletes it on every path: success, compile or link errors, and
// exceptions in between.
class ShaderObject {
public:
  explicit ShaderObject(GLenum stage) : mId(glCreateShader(stage)) {}
  ~ShaderObject() { if (mId) glDeleteShader(mId); }
  ShaderObject(ShaderObject&& o) noexcept : mId(std::exchange(o.mId, 0)) {}
  ShaderObject& operator=(ShaderObject&&) = delete;
  ShaderObject(const ShaderObject&) = delete;
  ShaderObject& operator=(const ShaderObject&) = delete;
  GLuint id() const { return mId; }

private:
  GLuint mId = 0;
};

ShaderObject compileStage(GLenum stage, const std::vector<std::string>& keys, const ShaderDefines& defines,
                          const SourceReader& read, const std::string& label) {
  ExpandedSource src = expandIncludes(keys, read);
  const std::string text = "#version 450 core\n" + defines.prelude() + src.text;
  ShaderObject shader(stage);
  const char* ptr = text.c_str();
  glShaderSource(shader.id(), 1, &ptr, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader.id(), length, nullptr, log.data());
    throw Error(fmt::format("shader '{}' failed to compile:\n{}", label, remapShaderLog(log.c_str(), src.files)));
  }
  return shader;
}

}  // namespace

gl::Program ShaderLibrary::build(const ProgramDesc& desc) const {
  const SourceReader read = [this](std::string_view key) { return source(key); };
  std::vector<ShaderObject> shaders;  // deleted when this returns or throws
  if (!desc.compute.empty()) shaders.push_back(compileStage(GL_COMPUTE_SHADER, desc.compute, desc.defines, read, desc.label));
  if (!desc.vertex.empty()) shaders.push_back(compileStage(GL_VERTEX_SHADER, desc.vertex, desc.defines, read, desc.label));
  if (!desc.fragment.empty()) shaders.push_back(compileStage(GL_FRAGMENT_SHADER, desc.fragment, desc.defines, read, desc.label));
  PN_CHECK(!shaders.empty(), fmt::format("program '{}' has no stages", desc.label));
  const GLuint program = glCreateProgram();
  for (const ShaderObject& s : shaders) glAttachShader(program, s.id());
  glLinkProgram(program);
  for (const ShaderObject& s : shaders) glDetachShader(program, s.id());
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw Error(fmt::format("program '{}' failed to link:\n{}", desc.label, log.c_str()));
  }
  return gl::Program(desc.label, program, !desc.compute.empty());
}

const gl::Program& ShaderLibrary::program(const ProgramDesc& desc) {
  auto it = mCache.find(desc);
  if (it != mCache.end()) return it->second;
  return mCache.emplace(desc, build(desc)).first->second;
}

std::vector<std::string> ShaderLibrary::reloadAll() {
  std::vector<std::string> errors;
  for (auto& [desc, program] : mCache) {
    try {
      program = build(desc);
    } catch (const Error& e) {
      errors.emplace_back(e.what());
    }
  }
  return errors;
}

}  // namespace penumbra
