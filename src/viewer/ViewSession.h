#pragma once
// The viewer's model, without any UI: the scene being viewed, the technique, every parameter
// value and the Renderer. The panels and the script runner both change the view through it,
// so a script does exactly what a click does.
#include <penumbra/Params.h>
#include <penumbra/Renderer.h>
#include <penumbra/Technique.h>

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::gl { class Context; }

namespace penumbra::viewer {

/// One panel's worth of parameters.
struct ParamGroup {
  std::string title;  ///< "Scene", "Projection: uniform", "Filter: hard"
  std::span<const ParamDesc> descs;
};

class ViewSession {
public:
  /// Takes a prepared scene and technique (penumbra::app::makeSetup), uploads the scene.
  /// Throws a usage Error when the technique cannot shadow a light of the scene.
  ViewSession(gl::Context& context, Scene scene, const Technique& technique);

  Renderer& renderer() { return mRenderer; }
  const Renderer& renderer() const { return mRenderer; }
  /// The scene as viewed now (camera and lights as moved).
  const Scene& scene() const { return mScene; }
  /// The technique as set now (every light runs it, with its own settings merged in).
  const Technique& technique() const { return mTechnique; }
  const std::string& projectionId() const { return mTechnique.projection(); }
  const std::string& filterId() const { return mTechnique.filter(); }
  int shadowMapSize() const { return mTechnique.mapSize(); }
  void setShadowMapSize(int texels);

  /// Each throws Error (usage for unknown ids / refused pairs) and leaves the view unchanged.
  void loadScene(const std::string& nameOrPath);
  void setProjection(const std::string& id);
  void setFilter(const std::string& id);

  /// Makes the technique again from the registry's entry of its filter, after that entry was
  /// replaced (a technique folder's description reloaded): the parameters follow the new
  /// table, the values set before are kept where the new table has them and takes them.
  /// Returns the keys whose values it refused (now at their defaults). Throws as setFilter().
  std::vector<std::string> refreshFilter();

  std::vector<ParamGroup> paramGroups();
  float paramValue(const ParamDesc& desc);
  /// Sets a projection, filter or scene parameter; remembered across technique switches.
  void setParam(const ParamDesc& desc, float value);
  /// "key=value" as on the command line; throws a usage Error for unknown keys/bad values.
  void setParam(const std::string& assignment);

  /// Camera and light edits: take effect at the next render().
  Camera& camera() { ++mVersion; return mScene.camera; }
  /// The selected light (what the light panels, the script's `light` actions and right-drag
  /// edit), writable; edits through it are not checked (setLight() checks).
  Light& light();
  std::vector<Light>& lights() { ++mVersion; return mScene.lights; }

  /// Lights (docs/viewer.md, "Lights"). The selection is an index into scene().lights; it is
  /// 0 after a scene loads. Each throws a usage Error and leaves the lights unchanged when the
  /// edit cannot be made.
  size_t selectedLight() const { return mSelected; }
  /// Light `index`; a usage Error naming the scene's lights when there is none of that index.
  const Light& lightAt(size_t index) const;
  void selectLight(size_t index);
  /// Appends a light (at most kMaxShadowedLights) and selects it. Refused if lightProblem()
  /// finds one or the technique cannot shadow it (csm and a point light).
  void addLight(const Light& light);
  /// Removes light `index` (never the last one left). The selection stays on the light it was
  /// on; if that was the removed one, on the one before it (or the new light 0).
  void removeLight(size_t index);
  /// Replaces light `index`, with addLight()'s checks.
  void setLight(size_t index, const Light& light);
  /// The renderer's debug images of the selected light (light 0's until a frame has it).
  std::vector<DebugImage> debugImages() const;
  /// The light whose images debugImages() lists: the selection, or the last light the last
  /// frame had.
  size_t shownLight() const;

  /// Animation (docs/viewer.md, "Time"). The scene's time in seconds, in [0, duration()]; 0 when
  /// a scene loads. duration() is 0 for a still scene.
  float time() const { return mTimeS; }
  float duration() const { return mScene.animation.durationS(); }
  /// Poses the scene at `timeS` (clamped to [0, duration()]): animated objects, lights and, when
  /// cameraFollows(), the camera move; an edit to an animated light lasts until the next pose.
  /// A `jump` (a scrub, a loop back to the start; not playback's step) that moves the camera is
  /// a camera cut for the next frame.
  void setTime(float timeS, bool jump = true);
  /// The next frame follows a camera jump: temporal accumulation starts afresh
  /// (RenderOptions::cameraCut).
  void cutCamera() { mCameraCut = true; }
  bool cameraCutPending() const { return mCameraCut; }
  /// Whether setTime() moves the camera along the scene's camera animation (if it has one).
  bool cameraFollows() const { return mCameraFollows; }
  /// Following again puts the camera where the animation has it now.
  void setCameraFollows(bool follows);
  bool animatesCamera() const { return !mScene.animation.camera.empty(); }

  /// Renders a width × height frame of the current state; `litView` = what the lit pass writes
  /// (RenderOptions::debugView). Throws Error on GL/shader failures.
  void render(int width, int height, int litView);
  bool hasFrame() const { return mHasFrame; }

  /// Changes whenever anything that affects the image changes (a stale-heatmap check).
  uint64_t version() const { return mVersion; }

private:
  /// Returns the remembered keys the new technique refused (out of its range), forgotten.
  std::vector<std::string> rebuildTechnique(const std::string& projectionId, const std::string& filterId);
  /// Throws a usage Error naming `which` if the light is not one to add or keep.
  void checkLight(const Light& light, const std::string& which);
  /// Gives the scene's lights that have none an id of their own (Light::id), so that each keeps
  /// its maps when another is removed.
  void nameLights();

  Renderer mRenderer;
  Scene mScene;
  Technique mTechnique;
  /// Values the user set, by key; re-applied when a technique is rebuilt.
  std::map<std::string, float, std::less<>> mRemembered;
  uint64_t mVersion = 1;
  bool mHasFrame = false;
  size_t mSelected = 0;
  float mTimeS = 0.0f;
  bool mCameraFollows = true;
  bool mCameraCut = false;
};

}  // namespace penumbra::viewer
