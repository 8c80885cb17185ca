#pragma once
// `penumbra view`: a GLFW window with Dear ImGui panels around the Renderer's output.
//  - Panels (Panels.cpp): scene, projection, filter and every parameter as a widget generated
//    from its ParamDesc; lights (LightsPanel.cpp); camera; debug views; per-pass times; shaders;
//    heatmap; save.
//  - The parts, one job each, that the panels and the script take by reference: the camera rig
//    (CameraRig.h), playback (Playback.h), the heatmap and reference (HeatmapView.h), hot reload
//    (HotReload.h), the script runner (ScriptRunner.h), the status line (StatusLine.h).
//  - The view (this file): owns the parts and wires them to the window: the main view + an
//    inset (any Renderer::debugImages() entry, the colour output or the error heatmap), the
//    split view, screenshots, and the scripted mode (Script.h) used by tests and demos.
#include "platform/Context.h"
#include "gl/Objects.h"
#include "viewer/CameraRig.h"
#include "viewer/DebugDisplay.h"
#include "viewer/HeatmapView.h"
#include "viewer/HotReload.h"
#include "viewer/Playback.h"
#include "viewer/ScriptRunner.h"
#include "viewer/Script.h"
#include "viewer/StatusLine.h"
#include "viewer/ViewSession.h"

#include <penumbra/Reference.h>

#include <array>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::viewer {

struct ViewerOptions {
  int width = 1280, height = 720;  ///< window size in pixels
  int frames = 0;                  ///< stop after this many frames; 0 = no limit
  std::vector<ScriptAction> script;
  bool scripted = false;           ///< --script given: exit after its last action; failures are fatal
  bool showUi = true;
  std::optional<std::filesystem::path> shaderTree;  ///< hot reload from this source tree
  /// Reload the technique folders' GLSL when it is saved (with or without a shader tree).
  bool reloadTechniqueFolders = true;
  bool vsync = true;
  bool verbose = false;
};

/// Names of the views that are not Renderer::debugImages() entries. The lit-pass views
/// (RenderOptions::debugView: shaded, cascades, texel-density) are the colour output.
inline constexpr const char* kShadedView = "shaded";
inline constexpr const char* kNoInset = "none";
/// The shadow-map sizes (texels per side) the panels offer: one light's all of them (a scene file's
/// mapSize), the technique's from kMinDefaultsMapSizeTexels (the command line's --shadow-map).
inline constexpr std::array<int, 7> kShadowMapSizes = {256, 512, 1024, 2048, 4096, 8192, 16384};

/// True for the lit pass's views (shaded, cascades, texel-density): the colour output.
bool isLitView(std::string_view name);

/// The panel groups, one tab each; the script's `panel NAME` opens one.
enum class Panel { Technique, Filter, Lights, Camera, Views, Timings, Tools };
struct PanelInfo {
  Panel panel;
  const char* id;     ///< script name
  const char* title;  ///< tab label
};
inline constexpr PanelInfo kPanels[] = {{Panel::Technique, "technique", "Technique"},
                                        {Panel::Filter, "filter", "Filter"},
                                        {Panel::Lights, "lights", "Lights"},
                                        {Panel::Camera, "camera", "Camera"},
                                        {Panel::Views, "views", "Views"},
                                        {Panel::Timings, "timings", "Timings"},
                                        {Panel::Tools, "tools", "Tools"}};

class Viewer final : private ScriptedViewer {
public:
  /// Opens the window (throws Error if no 4.5 context), then the session on `scene`.
  Viewer(Scene scene, const Technique& technique, ViewerOptions options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  /// Runs until the window closes, the frame limit is reached or the script ends. Throws Error
  /// for a script failure. Returns the exit code.
  int run();

private:
  struct ViewState {  // what one of the two view slots shows and how
    std::string name;
    DisplaySettings settings;
    /// The name was found at least once: when a later technique lacks it (sdf has no
    /// shadow-map), the slot waits for it instead of failing; a name never found is a typo.
    bool seen = false;
  };
  /// Where the open panel's content ends, for `print layout` (window pixels).
  struct PanelLayout {
    std::string panel;
    float contentBottom = 0.0f, windowHeight = 0.0f, scrollMax = 0.0f;
  };

  bool frame();
  void drawFrame();  ///< between ImGui's NewFrame and the buffer swap
  void layout();
  void handleInput(float dtSeconds);
  void renderFrame();
  void drawViews();
  void recordTimings(double frameMs);

  // Actions shared by the panels and the script (ScriptedViewer). They report problems in the
  // status line (and, when scripted, on stdout) instead of throwing, except for unknown names.
  bool selectScene(const std::string& nameOrPath) override;
  bool selectProjection(const std::string& id) override;
  bool selectFilter(const std::string& id) override;
  void flipReference() override;  ///< R: technique ↔ reference (a heatmap first when there is none)
  /// Split view: the right half of the view shows `filter` with `projection` ("" = off).
  bool setSplit(const std::string& filter, const std::string& projection) override;
  void renderSplit(int width, int height);
  void setView(ViewState& view, const std::string& name, const char* slot);
  void screenshotView(const std::filesystem::path& path);
  void screenshotWindow(const std::filesystem::path& path);
  void screenshotInset(const std::filesystem::path& path);  ///< with its labels (after ImGui)
  void saveSettings(const std::filesystem::path& path) override;
  std::filesystem::path nextScreenshotPath() const;
  const gl::Texture* findView(const std::string& name) const;
  int litView() const;  ///< RenderOptions::debugView for the main view
  std::vector<std::string> viewNames() const;

  // The rest of what the script asks of the viewer (ScriptedViewer; the runner dispatches).
  void showView(bool inset, const std::string& name) override;
  void openPanel(const std::string& id) override;
  void requestScreenshot(Shot shot, const std::filesystem::path& path) override;
  void showUi(bool show) override { mOptions.showUi = show; }
  double lastFrameMs() const override { return mLastFrameMs; }

  // Lights (LightsPanel.cpp): the light list and the selected light's editor, labels over the
  // views that name the light and the layer (cube face, cascade) shown, the `light` action.
  void drawLightsPanel();
  void drawLightList();  ///< the list, + sun/spot/point, Remove
  void applyLightEdit(size_t selected, const Light& l);
  void drawLightMapsReport(size_t selected, const Light& l);  ///< what its maps got, the inset button
  void drawViewLabels();
  void executeLight(const ScriptAction& a) override;

  // Panels (Panels.cpp).
  void drawPanels();
  void drawTechniquePanel();
  /// The parameter groups [first, last) of ViewSession::paramGroups().
  void drawParams(size_t first, size_t last);
  void drawViewsPanel();
  void drawViewSettings(const char* id, ViewState& view, bool allowNone);
  void drawTimingPanel();
  void drawToolsPanel();
  void drawSplitControls();
  void loadFont();
  std::string layoutText() const override;  ///< `print layout`: the open panel's extent, the font's coverage

  // Legends (Legends.cpp): what the colours of the main view and the inset mean.
  void drawLegends();
  /// The legend of one view slot, its corner at `anchor` (window pixels from the top-left) taken
  /// at `pivot` (0..1 of its size), e.g. (0, 1) = lower-left. Returns the legend's top edge
  /// (window pixels from the top), or nothing where the view needs no legend (`shaded`).
  std::optional<float> drawLegend(const char* id, const ViewState& view, const glm::vec2& range, const glm::vec2& anchor,
                  const glm::vec2& pivot);

  ViewerOptions mOptions;
  gl::WindowContext mWindow;
  ViewSession mSession;
  DebugDisplay mDisplay;
  StatusLine mStatus;
  HotReload mHotReload;
  CameraRig mCamera{mStatus};
  Playback mPlayback{mSession, mCamera, mStatus};
  HeatmapView mHeatmap{mSession, mStatus, mOptions.scripted};
  std::unique_ptr<ViewSession> mSplit; ///< the right half's technique, when the view is split
  std::string mSplitLabel;

  std::optional<Panel> mSelectPanel;   ///< a tab to open on the next frame (script, keys)
  PanelLayout mLayout;

  // Layout (window pixels, origin lower-left).
  glm::ivec2 mFramebuffer{0};
  glm::ivec4 mViewRect{0}, mInsetRect{0};
  float mSidebarWidth = 380.0f;
  bool mSidebarFitted = false;  ///< widened once to hold every tab's title
  float mRenderScale = 1.0f;

  ViewState mMain{kShadedView, {}, true}, mInset{kNoInset, {}, true};
  glm::vec2 mMainRange{0.0f}, mInsetRange{0.0f};

  // Timings.
  std::string mRenderError;
  std::map<std::string, std::deque<float>> mPassHistory;
  std::deque<float> mFrameHistory;
  double mLastFrameMs = 0.0;
  long mFrameCount = 0;

  // Script and screenshot requests for the current frame.
  ScriptRunner mScript{mOptions.script, {*this, mSession, mCamera, mPlayback, mHeatmap, mHotReload, mStatus}};
  std::optional<std::filesystem::path> mViewShot, mWindowShot, mInsetShot;
  char mSavePath[512] = {};
  char mScenePath[512] = {};
};

}  // namespace penumbra::viewer
