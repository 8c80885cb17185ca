// The viewer's script format (src/viewer/Script.h): what parses, and what fails with file:line.
#include "viewer/Script.h"
#include "viewer/Viewer.h"

#include <penumbra/Error.h>

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::viewer;

namespace {
std::string errorOf(std::string_view text) {
  try {
    parseScript(text, "s.txt");
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ViewerScript, ParsesActionsSkippingCommentsAndBlankLines) {
  const auto actions = parseScript(
      "# a demo\n\nscene pen\n  filter   pcss   # soft\nset pcss.blockerSamples=32\ncamera orbit 30 20 4.5\n"
      "light angles -40 35\nwait 3\nscreenshot out/a.png\nprint gl-objects\nheatmap\nheatmap 16\nquit\n",
      "demo.txt");
  ASSERT_EQ(actions.size(), 11u);
  EXPECT_EQ(actions[0].verb, "scene");
  EXPECT_EQ(actions[0].line, 3);
  EXPECT_EQ(actions[1].verb, "filter");
  ASSERT_EQ(actions[1].args.size(), 1u);
  EXPECT_EQ(actions[1].args[0], "pcss");
  EXPECT_EQ(actions[1].where, "demo.txt:4");
  EXPECT_EQ(actions[3].args.size(), 4u);
  EXPECT_FLOAT_EQ(scriptFloat(actions[3], 3), 4.5f);
  EXPECT_EQ(scriptInt(actions[5], 0, 0, 10), 3);
  EXPECT_EQ(actions[6].args[0], "out/a.png");
}

TEST(ViewerScript, MistakesNameTheLine) {
  EXPECT_NE(errorOf("scene pen\nzoom 2\n").find("s.txt:2: unknown action 'zoom'"), std::string::npos);
  EXPECT_NE(errorOf("wait\n").find("s.txt:1: wait: expected wait FRAMES"), std::string::npos);
  EXPECT_NE(errorOf("wait -1\n").find("s.txt:1"), std::string::npos);
  EXPECT_NE(errorOf("wait 1.5\n").find("not a whole number"), std::string::npos);
  EXPECT_NE(errorOf("set pcss.blockerSamples\n").find("KEY=VALUE"), std::string::npos);
  EXPECT_NE(errorOf("camera orbit 1 2\n").find("s.txt:1: camera"), std::string::npos);
  EXPECT_NE(errorOf("camera spin 1 2 3\n").find("expected camera"), std::string::npos);
  EXPECT_NE(errorOf("camera orbit a 2 3\n").find("'a' is not a number"), std::string::npos);
  EXPECT_NE(errorOf("light direction 0 -1\n").find("s.txt:1: light"), std::string::npos);
  EXPECT_NE(errorOf("ui maybe\n").find("on or off"), std::string::npos);
  EXPECT_NE(errorOf("print everything\n").find("gl-objects"), std::string::npos);
  EXPECT_NE(errorOf("screenshot a.png b.png\n").find("expected screenshot PATH"), std::string::npos);
  EXPECT_EQ(errorOf("screenshot a.png\n"), "");
}

TEST(ViewerScript, HelpListsEveryAction) {
  const std::string help = scriptHelp();
  for (const char* verb : {"scene", "filter", "projection", "set", "camera", "light", "view", "inset", "flip", "split", "panel", "wait", "screenshot",
                           "screenshot-window", "screenshot-inset", "print", "heatmap", "wait-heatmap", "reload", "save", "ui", "quit"})
    EXPECT_TRUE(help.find(std::string("\n  ") + verb + " ") != std::string::npos ||
                help.find(std::string("\n  ") + verb + "\n") != std::string::npos ||
                help.rfind(std::string("  ") + verb + " ", 0) == 0)
        << verb;
}

TEST(ViewerScript, LightActionsParse) {
  const auto actions = parseScript(
      "light select 1\nlight add point\nlight add sun\nlight remove 0\nlight set 1 position 1 2 3\n"
      "light set 0 color 1,0.5,0.25\nlight set 1 castsShadow off\nlight set 2 mapSize 512\nlight set 0 type spot\n"
      "light angles -40 35\nlight position 0 3 0\n",
      "s.txt");
  ASSERT_EQ(actions.size(), 11u);
  EXPECT_EQ(actions[4].args, (std::vector<std::string>{"set", "1", "position", "1", "2", "3"}));
  EXPECT_EQ(scriptInt(actions[0], 1, 0, 15), 1);
}

TEST(ViewerScript, LightMistakesNameTheLineAndTheProblem) {
  EXPECT_NE(errorOf("wait 1\nlight set 0 colour 1 1 1\n").find("s.txt:2: light: unknown light key 'colour'"), std::string::npos);
  EXPECT_NE(errorOf("light select 16\n").find("'16' is not a whole number in 0..15"), std::string::npos);
  EXPECT_NE(errorOf("light select one\n").find("'one' is not a whole number"), std::string::npos);
  EXPECT_NE(errorOf("light remove -1\n").find("s.txt:1: light"), std::string::npos);
  EXPECT_NE(errorOf("light remove\n").find("expected light select N"), std::string::npos);
  EXPECT_NE(errorOf("light add lamp\n").find("unknown light type 'lamp' (sun, spot or point)"), std::string::npos);
  EXPECT_NE(errorOf("light set 0 size\n").find("expected light set N KEY VALUE"), std::string::npos);
  EXPECT_NE(errorOf("light set 0 size big\n").find("'big' is not a number"), std::string::npos);
  EXPECT_NE(errorOf("light set 0 position 1 2\n").find("X Y Z or X,Y,Z"), std::string::npos);
  EXPECT_NE(errorOf("light set 0 mapSize 100.5\n").find("whole number of texels"), std::string::npos);
  EXPECT_NE(errorOf("light set 0 castsShadow maybe\n").find("on or off"), std::string::npos);
  EXPECT_NE(errorOf("light dim 0\n").find("expected light"), std::string::npos);
}

// `panel NAME` takes exactly the viewer's tab ids; `split` a filter (and projection) or off.
TEST(ViewerScript, PanelAndSplitActions) {
  for (const viewer::PanelInfo& p : viewer::kPanels)
    EXPECT_NO_THROW(viewer::parseScript(std::string("panel ") + p.id + "\n", "s.txt")) << p.id;
  EXPECT_THROW(viewer::parseScript("panel sidebar\n", "s.txt"), Error);
  EXPECT_THROW(viewer::parseScript("panel light\n", "s.txt"), Error);  // the tabs are lights and camera
  EXPECT_NO_THROW(viewer::parseScript("split vsm\nsplit pcss csm\nsplit off\nflip\nprint layout\nprint lights\n", "s.txt"));
  EXPECT_THROW(viewer::parseScript("split off now\n", "s.txt"), Error);
  EXPECT_THROW(viewer::parseScript("split\n", "s.txt"), Error);
}
