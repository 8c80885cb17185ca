#include "shader/ShaderLibrary.h"

#include <penumbra/Error.h>

#include <gtest/gtest.h>

#include <map>

using namespace penumbra;

namespace {

SourceReader readerFor(const std::map<std::string, std::string>& files) {
  return [files](std::string_view key) -> std::optional<std::string> {
    auto it = files.find(std::string(key));
    if (it == files.end()) return std::nullopt;
    return it->second;
  };
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(ShaderInclude, ExpandsNestedIncludesWithLineDirectives) {
  const auto read = readerFor({{"main.glsl", "a\n#include \"lib.glsl\"\nb\n"}, {"lib.glsl", "#pragma once\nlib\n"}});
  const ExpandedSource s = expandIncludes({"main.glsl"}, read);
  ASSERT_EQ(s.files.size(), 2u);
  EXPECT_EQ(s.files[0], "main.glsl");
  EXPECT_EQ(s.files[1], "lib.glsl");
  EXPECT_NE(s.text.find("#line 1 1\n\nlib\n#line 3 0\nb"), std::string::npos) << s.text;
}

TEST(ShaderInclude, PragmaOnceIncludesOnce) {
  const auto read = readerFor({{"main.glsl", "#include \"lib.glsl\"\n#include \"lib.glsl\"\n"}, {"lib.glsl", "#pragma once\nLIB\n"}});
  const ExpandedSource s = expandIncludes({"main.glsl"}, read);
  EXPECT_EQ(s.text.find("LIB"), s.text.rfind("LIB"));
}

TEST(ShaderInclude, MissingFileIsAnErrorNamingTheIncluder) {
  const auto read = readerFor({{"main.glsl", "x\n#include \"gone.glsl\"\n"}});
  const std::string e = errorOf([&] { expandIncludes({"main.glsl"}, read); });
  EXPECT_NE(e.find("main.glsl:2"), std::string::npos) << e;
  EXPECT_NE(e.find("gone.glsl"), std::string::npos) << e;
}

TEST(ShaderInclude, RecursionIsAnError) {
  const auto read = readerFor({{"a.glsl", "#include \"b.glsl\"\n"}, {"b.glsl", "\n#include \"a.glsl\"\n"}});
  const std::string e = errorOf([&] { expandIncludes({"a.glsl"}, read); });
  EXPECT_NE(e.find("recursive"), std::string::npos) << e;
  EXPECT_NE(e.find("b.glsl:2"), std::string::npos) << e;
}

TEST(ShaderInclude, DriverLogsMapToFileAndLine) {
  const std::vector<std::string> files = {"passes/x.glsl", "common/y.glsl"};
  EXPECT_EQ(remapShaderLog("1:12(3): error: undeclared identifier", files), "common/y.glsl:12: error: undeclared identifier");
  EXPECT_EQ(remapShaderLog("0(7) : error C1008: bad", files), "passes/x.glsl:7: error C1008: bad");
}

TEST(ShaderInclude, EveryEmbeddedShaderExpands) {
  ShaderLibrary lib;
  const std::vector<std::string> keys = lib.keys();
  EXPECT_GT(keys.size(), 5u);
  for (const std::string& k : keys) {
    if (k.ends_with(".h")) continue;
    EXPECT_NO_THROW(expandIncludes({k}, [&](std::string_view key) { return lib.source(key); })) << k;
  }
}
