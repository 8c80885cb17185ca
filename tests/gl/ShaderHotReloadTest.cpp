// The viewer's shader hot reload (src/viewer/ShaderWatcher.h): an edit in the source tree is
// picked up, a broken edit keeps the last good program and reports file:line, a fix recovers,
// and no GL object is leaked on the way.
#include "GlFixture.h"

#include "gl/Debug.h"

#include "viewer/ShaderWatcher.h"

#include <penumbra/Error.h>
#include <penumbra/Technique.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>
#include <unistd.h>

using namespace penumbra;

namespace {

constexpr const char* kKey = "passes/viewer_range.comp.glsl";

void writeShader(const std::filesystem::path& file, const std::string& text, int secondsAhead) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  // File times may be coarse: set one that differs from the last for sure.
  std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now() + std::chrono::seconds(secondsAhead));
}

/// The test context's debug callback records the driver's compile error as a GL error; it
/// belongs to the test that broke a shader on purpose, not to the next one that checks for errors.
void forgetDeliberateCompileError() {
  try {
    gl::throwIfGlError("the deliberately broken shader");
  } catch (const Error&) {
  }
}

}  // namespace

TEST(ShaderHotReload, BrokenEditKeepsLastGoodProgramAndFixRecovers) {
  test::glContext();
  ShaderLibrary library;
  const std::string original = library.source(kKey).value();
  const auto tree = std::filesystem::temp_directory_path() / ("penumbra-hotreload-" + std::to_string(getpid()));
  std::filesystem::remove_all(tree);
  std::filesystem::create_directories(tree / "shaders/passes");
  const auto file = tree / "shaders" / kKey;
  writeShader(file, original, 0);

  viewer::ShaderWatcher watcher(library, tree);
  ProgramDesc desc;
  desc.label = "hot reload test";
  desc.compute = {kKey};
  desc.defines.set("PN_VIEWER_SOURCE", 0);
  const GLuint first = library.program(desc).id();
  const int objects = gl::liveObjectCount();
  EXPECT_FALSE(watcher.poll());  // nothing changed (and within the poll interval)

  // A syntax error on line 3 of the file: the reload reports it there and keeps the program.
  std::string broken = original;
  broken.insert(broken.find('\n', broken.find('\n') + 1) + 1, "this is not GLSL;\n");
  writeShader(file, broken, 2);
  const std::vector<std::string> errors = watcher.reload();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find(std::string(kKey) + ":3:"), std::string::npos) << errors[0];
  EXPECT_EQ(library.program(desc).id(), first);
  EXPECT_EQ(gl::liveObjectCount(), objects);
  forgetDeliberateCompileError();

  // Fixed: poll() notices the new time after its interval and builds a new program.
  writeShader(file, original + "\n// edited\n", 4);
  std::this_thread::sleep_for(viewer::ShaderWatcher::kPollInterval + std::chrono::milliseconds(50));
  EXPECT_TRUE(watcher.poll());
  EXPECT_TRUE(watcher.errors().empty());
  EXPECT_NE(library.program(desc).id(), first);
  EXPECT_EQ(gl::liveObjectCount(), objects);
  EXPECT_EQ(watcher.reloads(), 2);
  std::filesystem::remove_all(tree);
}

// A technique folder's GLSL (docs/own-technique.md) is watched with no source tree: the library
// reads it from its absolute path at every build, so a saved edit is the next program, and a
// broken one is reported at that path and line.
TEST(ShaderHotReload, ATechniqueFoldersGlslIsReloadedOnSave) {
  test::glContext();
  const auto folder = std::filesystem::temp_directory_path() / ("penumbra-hotreload-folder-" + std::to_string(getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "technique.json") << R"({"id": "hot-reload-test", "description": "a test", "maps": ["depth"]})";
  const auto file = std::filesystem::canonical(folder) / "visibility.glsl";
  const std::string shader = "layout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer B { float v; };\nvoid main() { v = 1.0; }\n";
  writeShader(file, shader, 0);
  ASSERT_EQ(loadTechniqueFolder(folder), "hot-reload-test");

  ShaderLibrary library;
  viewer::ShaderWatcher watcher(library, {});  // no source tree: the folders only
  ProgramDesc desc;
  desc.label = "technique folder reload test";
  desc.compute = {file.string()};
  const GLuint first = library.program(desc).id();

  std::string broken = shader;
  broken.insert(broken.find('\n', broken.find('\n') + 1) + 1, "this is not GLSL;\n");
  writeShader(file, broken, 2);
  std::this_thread::sleep_for(viewer::ShaderWatcher::kPollInterval + std::chrono::milliseconds(50));
  EXPECT_TRUE(watcher.poll());
  ASSERT_EQ(watcher.errors().size(), 1u);
  EXPECT_NE(watcher.errors()[0].find(file.string() + ":3:"), std::string::npos) << watcher.errors()[0];
  EXPECT_EQ(library.program(desc).id(), first);
  forgetDeliberateCompileError();

  writeShader(file, shader + "// saved again\n", 4);
  std::this_thread::sleep_for(viewer::ShaderWatcher::kPollInterval + std::chrono::milliseconds(50));
  EXPECT_TRUE(watcher.poll());
  EXPECT_TRUE(watcher.errors().empty());
  EXPECT_NE(library.program(desc).id(), first);
  std::filesystem::remove_all(folder);
}
