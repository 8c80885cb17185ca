// The viewer's model (src/viewer/ViewSession.h): technique switches keep the user's parameter
// values, failures leave the view as it was, and the renderer lists every debug image.
#include "GlFixture.h"

#include "gl/Objects.h"
#include "viewer/ViewSession.h"

#include "shared/Enums.h"

#include <penumbra/Error.h>

#include <gtest/gtest.h>

#include <algorithm>

using namespace penumbra;
using namespace penumbra::viewer;

namespace {
ViewSession makeSession() {
  return ViewSession(test::glContext(), makeBuiltinScene("pen"), Technique("uniform", "hard").setMapSize(256));
}
}  // namespace

TEST(ViewSession, SwitchingFiltersKeepsTheValuesTheUserSet) {
  ViewSession s = makeSession();
  s.setParam("hard.constantBias=0.001");
  EXPECT_FLOAT_EQ(s.renderer().technique().get("hard.constantBias"), 0.001f);
  for (const std::string& id : filterIds()) {
    s.setFilter(id);
    EXPECT_EQ(s.filterId(), id);
    EXPECT_EQ(s.renderer().technique().filter(), id);
  }
  s.setFilter("hard");
  EXPECT_FLOAT_EQ(s.renderer().technique().get("hard.constantBias"), 0.001f);
  // The last registered projection that can shadow pen's spot light.
  std::string last;
  for (const std::string& id : projectionIds())
    if (projectionIncompatibility(id, makeBuiltinScene("pen").light()).empty()) last = id;
  s.setProjection(last);
  EXPECT_EQ(s.renderer().technique().projection(), last);
  EXPECT_FLOAT_EQ(s.renderer().technique().get("hard.constantBias"), 0.001f);
}

TEST(ViewSession, FailuresLeaveTheViewAsItWas) {
  ViewSession s = makeSession();
  const uint64_t v = s.version();
  EXPECT_THROW(s.setFilter("blurry"), Error);
  EXPECT_EQ(s.filterId(), "hard");
  EXPECT_EQ(s.renderer().technique().filter(), "hard");
  EXPECT_THROW(s.loadScene("/no/such/scene.json"), Error);
  EXPECT_EQ(s.scene().name, "pen");
  EXPECT_THROW(s.setParam("hard.nothing=1"), Error);
  EXPECT_THROW(s.setParam("hard.slopeBias=99"), Error);
  EXPECT_EQ(s.version(), v);
}

TEST(ViewSession, SceneParametersMoveTheLightAndCountAsChanges) {
  ViewSession s = makeSession();
  const uint64_t v = s.version();
  s.setParam("light.size=0.3");
  EXPECT_FLOAT_EQ(s.scene().light().size, 0.3f);
  EXPECT_GT(s.version(), v);
  const ParamDesc& size = sceneParamDescs().front();
  EXPECT_FLOAT_EQ(s.paramValue(size), 0.3f);
  s.loadScene("boxes");
  EXPECT_EQ(s.scene().name, "boxes");
  EXPECT_EQ(s.filterId(), "hard");  // the technique stays
}

TEST(ViewSession, RendersAndListsDebugImages) {
  ViewSession s = makeSession();
  EXPECT_FALSE(s.hasFrame());
  s.render(64, 32, PN_VIEW_SHADED);
  EXPECT_TRUE(s.hasFrame());
  EXPECT_EQ(s.renderer().colorTexture().width(), 64);
  std::vector<std::string> names;
  for (const DebugImage& d : s.renderer().debugImages()) names.push_back(d.name);
  for (const char* n : {"visibility", "gbuffer-depth", "shadow-map"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  // Moving the camera does not re-upload the scene: no GL object is created.
  const int objects = gl::liveObjectCount();
  s.camera().position += glm::vec3(0.2f, 0.0f, 0.0f);
  s.render(64, 32, PN_VIEW_SHADED);
  EXPECT_EQ(gl::liveObjectCount(), objects);
}

// City's walking camera: a scrub (a jump) that moves the followed camera marks the next frame a
// camera cut, playback's step does not, nor a jump with the camera not following; the frame takes
// the mark and clears it.
TEST(ViewSession, JumpsOfAFollowedCameraAreCameraCuts) {
  ViewSession s(test::glContext(), makeBuiltinScene("city"), Technique("uniform", "hard").setMapSize(256));
  ASSERT_TRUE(s.animatesCamera());
  EXPECT_FALSE(s.cameraCutPending());
  s.setTime(1.0f / 30.0f, false);
  EXPECT_FALSE(s.cameraCutPending()) << "playback's step";
  s.setTime(3.0f);
  EXPECT_TRUE(s.cameraCutPending()) << "a scrub";
  s.render(32, 18, 0);
  EXPECT_FALSE(s.cameraCutPending()) << "the frame took it";
  s.setCameraFollows(false);
  s.setTime(5.0f);
  EXPECT_FALSE(s.cameraCutPending()) << "the camera stayed";
  s.cutCamera();
  EXPECT_TRUE(s.cameraCutPending());
}
