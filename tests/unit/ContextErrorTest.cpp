// The error when no headless OpenGL context can be made: one line naming every platform tried
// (Mesa's surfaceless, then the EGL device platform) with why each failed, and how to get Mesa's
// llvmpipe. Built without touching EGL, so it runs where EGL works too.
#include "platform/Context.h"

#include <gtest/gtest.h>

using namespace penumbra::gl;

namespace {

void expectOneLineWithTheFix(const std::string& message) {
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find("OpenGL 4.5 core"), std::string::npos) << message;
  EXPECT_NE(message.find("llvmpipe"), std::string::npos) << message;
  EXPECT_NE(message.find("apt-get install libegl-mesa0 libgl1-mesa-dri"), std::string::npos) << message;
}

}  // namespace

TEST(HeadlessContextError, NamesEveryPlatformAndWhyItFailed) {
  // A Mesa without llvmpipe's GL and no NVIDIA driver: the device platform's extension is absent.
  const std::string m = headlessContextError({{"EGL surfaceless", "eglInitialize failed (0x3001)"},
                                              {"EGL device", "extension EGL_EXT_platform_device missing"}});
  std::printf("%s\n", m.c_str());
  EXPECT_NE(m.find("EGL surfaceless (eglInitialize failed (0x3001))"), std::string::npos) << m;
  EXPECT_NE(m.find("EGL device (extension EGL_EXT_platform_device missing)"), std::string::npos) << m;
  EXPECT_LT(m.find("EGL surfaceless"), m.find("EGL device")) << "in the order they are tried: " << m;
  expectOneLineWithTheFix(m);
}

TEST(HeadlessContextError, ListsEachDeviceAndPlatformsWithoutARecordedAttempt) {
  const std::string m = headlessContextError({{"EGL device 0", "no display"},
                                              {"EGL device 1", "no OpenGL 4.5 core context (0x3004)"}});
  EXPECT_NE(m.find("EGL device (#0: no display; #1: no OpenGL 4.5 core context (0x3004))"), std::string::npos) << m;
  // A platform the constructor recorded nothing for is still named.
  EXPECT_NE(m.find("EGL surfaceless (not tried)"), std::string::npos) << m;
  expectOneLineWithTheFix(m);
  const std::string none = headlessContextError({});
  for (const char* platform : kHeadlessPlatforms) EXPECT_NE(none.find(std::string(platform) + " (not tried)"), std::string::npos) << none;
}
