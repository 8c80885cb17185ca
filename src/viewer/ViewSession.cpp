#include "viewer/ViewSession.h"

#include "viewer/LightEdit.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>
#include "techniques/Registry.h"
#include <penumbra/Technique.h>
#include <penumbra/SceneIO.h>

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace penumbra::viewer {
namespace {

std::string prefixOf(std::string_view key) { return std::string(key.substr(0, key.find('.'))); }

bool isSceneParam(std::string_view key) {
  const auto descs = sceneParamDescs();
  return std::any_of(descs.begin(), descs.end(), [&](const ParamDesc& d) { return d.key == key; });
}

// The scene's own `light.*` settings (makeSetup applies them for the first scene).
void applySceneLightParams(Scene& scene) {
  std::vector<std::pair<std::string, std::string>> light;
  for (const auto& kv : scene.shadow.params)
    if (prefixOf(kv.first) == "light") light.push_back(kv);
  Technique unused;  // light.* keys change the scene only
  applySettings(light, scene, unused);
}

}  // namespace

ViewSession::ViewSession(gl::Context& /*current: the renderer draws on it*/, Scene scene, const Technique& technique)
    : mScene(std::move(scene)), mTechnique(technique) {
  // What the command line set (and the scene's own values) is remembered like a widget edit.
  for (const Parameterized* p : {&technique.projectionValues(), &technique.filterValues()})
    for (const ParamDesc& d : p->paramDescs())
      if (p->param(d.key) != d.def) mRemembered[std::string(d.key)] = p->param(d.key);
  nameLights();
  mRenderer.setScene(mScene);
  mRenderer.setTechnique(mTechnique);
}

void ViewSession::nameLights() {
  uint64_t next = 1;
  for (const Light& l : mScene.lights) next = std::max(next, l.id + 1);
  for (Light& l : mScene.lights)
    if (l.id == 0) l.id = next++;
}

void ViewSession::setShadowMapSize(int texels) {
  if (texels < kMinMapSizeTexels) throw usageError(fmt::format("shadow map size {}: must be at least {}", texels, kMinMapSizeTexels));
  Technique t = mTechnique;
  t.setMapSize(texels);
  mRenderer.setTechnique(t);
  mTechnique = t;
  ++mVersion;
}

Light& ViewSession::light() {
  PN_CHECK(mSelected < mScene.lights.size(), "the scene has no light");
  ++mVersion;
  return mScene.lights[mSelected];
}

void ViewSession::checkLight(const Light& light, const std::string& which) {
  if (const std::string problem = lightProblem(light); !problem.empty()) throw usageError(fmt::format("{}: {}", which, problem));
  if (!light.castsShadow) return;
  if (const std::string why = mTechnique.forLight(light.shadow, which).problemWith(light); !why.empty())
    throw usageError(fmt::format("{}: {}", which, why));
}

const Light& ViewSession::lightAt(size_t index) const {
  if (index >= mScene.lights.size())
    throw usageError(fmt::format("there is no light {}: the scene has {} (0..{})", index, mScene.lights.size(), mScene.lights.size() - 1));
  return mScene.lights[index];
}

void ViewSession::selectLight(size_t index) {
  lightAt(index);  // throws when there is no such light
  mSelected = index;
}

void ViewSession::addLight(const Light& light) {
  if (mScene.lights.size() >= kMaxShadowedLights)
    throw usageError(fmt::format("the scene has {} lights, the most one frame shadows (kMaxShadowedLights)", mScene.lights.size()));
  checkLight(light, lightLabel(light, mScene.lights.size()));
  mScene.lights.push_back(light);
  mScene.lights.back().id = 0;  // a light of its own, whatever it was copied from
  nameLights();
  mSelected = mScene.lights.size() - 1;
  ++mVersion;
}

void ViewSession::removeLight(size_t index) {
  lightAt(index);  // throws when there is no such light
  if (mScene.lights.size() <= 1)
    throw usageError(fmt::format("cannot remove {}: it is the scene's only light, and a scene needs at least one",
                                 lightLabel(mScene.lights[index], index)));
  mScene.lights.erase(mScene.lights.begin() + static_cast<std::ptrdiff_t>(index));
  mScene.animation.removeLight(static_cast<uint32_t>(index));
  if (mSelected > index || (mSelected == index && index > 0)) --mSelected;
  ++mVersion;
}

void ViewSession::setLight(size_t index, const Light& light) {
  lightAt(index);  // throws when there is no such light
  checkLight(light, lightLabel(light, index));
  const uint64_t id = mScene.lights[index].id;  // the same light, changed: it keeps its maps
  mScene.lights[index] = light;
  mScene.lights[index].id = id;
  ++mVersion;
}

size_t ViewSession::shownLight() const {
  const size_t count = mRenderer.lightCount();
  return count == 0 ? 0 : std::min(mSelected, count - 1);
}

std::vector<DebugImage> ViewSession::debugImages() const { return mRenderer.debugImages(shownLight()); }

std::vector<std::string> ViewSession::rebuildTechnique(const std::string& projectionId, const std::string& filterId) {
  Technique t(projectionId, filterId);
  t.setMapSize(mTechnique.mapSize());
  std::vector<std::pair<std::string, std::string>> own;  // the scene's settings for this technique
  for (const auto& kv : mScene.shadow.params)
    if (prefixOf(kv.first) == projectionId || prefixOf(kv.first) == filterId) own.push_back(kv);
  t.setWhereOwn(own);
  std::vector<std::string> refused;  // a reloaded folder's table may have narrowed a range
  for (const auto& [key, value] : mRemembered)
    if (t.has(key) && t.owner(key) != ParamOwner::AddOn) {
      try {
        t.set(key, value);
      } catch (const Error&) {
        refused.push_back(key);
      }
    }
  for (const ParamDesc& d : t.addOnValues().paramDescs()) t.set(d.key, mTechnique.get(d.key));  // the add-ons stay as they are
  mRenderer.setTechnique(t);  // checks every light; throws before changing anything
  mTechnique = t;
  for (const std::string& key : refused) mRemembered.erase(key);
  ++mVersion;
  return refused;
}

std::vector<std::string> ViewSession::refreshFilter() { return rebuildTechnique(mTechnique.projection(), mTechnique.filter()); }

void ViewSession::setProjection(const std::string& id) { rebuildTechnique(id, mTechnique.filter()); }
void ViewSession::setFilter(const std::string& id) { rebuildTechnique(mTechnique.projection(), id); }

void ViewSession::loadScene(const std::string& nameOrPath) {
  LoadOptions options;
  options.groundUnderLoneModel = true;  // as the CLI
  Scene next = penumbra::loadScene(nameOrPath, options);
  applySceneLightParams(next);
  // What the new scene's file sets explicitly wins over values remembered from before.
  auto previousRemembered = mRemembered;
  for (const auto& kv : next.shadow.params) mRemembered.erase(kv.first);
  Scene previous = std::move(mScene);
  mScene = std::move(next);
  nameLights();
  try {
    mRenderer.setScene(mScene);
    rebuildTechnique(mTechnique.projection(), mTechnique.filter());
  } catch (...) {
    mScene = std::move(previous);
    mRemembered = std::move(previousRemembered);
    mRenderer.setScene(mScene);
    throw;
  }
  mHasFrame = false;
  mSelected = 0;
  mTimeS = 0.0f;
  ++mVersion;
}

void ViewSession::setCameraFollows(bool follows) {
  mCameraFollows = follows;
  if (!follows || !animatesCamera()) return;
  poseScene(mScene, mTimeS);  // the same pose again, with the camera this time
  mRenderer.setPose(mScene);
  mCameraCut = true;  // the camera jumps back onto its path
  ++mVersion;
}

void ViewSession::setTime(float timeS, bool jump) {
  timeS = std::clamp(timeS, 0.0f, duration());
  if (timeS == mTimeS) return;
  mTimeS = timeS;
  const Camera camera = mScene.camera;
  poseScene(mScene, timeS);  // moves only what is animated: the rest keeps its edits
  if (!mCameraFollows) mScene.camera = camera;
  if (jump && mCameraFollows && animatesCamera()) mCameraCut = true;
  mRenderer.setPose(mScene);
  ++mVersion;
}

std::vector<ParamGroup> ViewSession::paramGroups() {
  // light.count is the bench's: the viewer adds and removes lights one by one instead.
  static const std::vector<ParamDesc> kScene = [] {
    std::vector<ParamDesc> out;
    for (const ParamDesc& d : sceneParamDescs())
      if (d.key != "light.count") out.push_back(d);
    return out;
  }();
  std::vector<ParamGroup> groups = {{"Scene", kScene},
                                    {fmt::format("Projection: {}", mTechnique.projection()), mTechnique.projectionValues().paramDescs()},
                                    {fmt::format("Filter: {}", mTechnique.filter()), mTechnique.filterValues().paramDescs()}};
  for (const AddOnGroup& g : addOnGroups()) groups.push_back({std::string(g.label), g.params});
  return groups;
}

float ViewSession::paramValue(const ParamDesc& desc) {
  if (mTechnique.has(desc.key)) return mTechnique.get(desc.key);
  // Scene parameters have no getter of their own: light.size is the light's size.
  if (desc.key == "light.size" && !mScene.lights.empty()) return mScene.lights.front().size;
  if (auto it = mRemembered.find(desc.key); it != mRemembered.end()) return it->second;
  return desc.def;
}

void ViewSession::setParam(const ParamDesc& desc, float value) {
  checkParamValue(desc, value);
  if (isSceneParam(desc.key)) {
    Technique unused;  // a scene key changes the scene only
    applySettings({{std::string(desc.key), formatParamValue(desc, value)}}, mScene, unused);
  } else {
    if (!mTechnique.has(desc.key))
      throw usageError(fmt::format("parameter '{}' belongs to neither projection {} nor filter {}", desc.key, mTechnique.projection(),
                                   mTechnique.filter()));
    Technique t = mTechnique;
    t.set(desc.key, value);
    mRenderer.setTechnique(t);
    mTechnique = t;
    mRemembered[std::string(desc.key)] = value;
  }
  ++mVersion;
}

void ViewSession::setParam(const std::string& assignment) {
  const auto [key, text] = splitAssignment(assignment);
  for (const ParamGroup& g : paramGroups())
    for (const ParamDesc& d : g.descs)
      if (d.key == key) return setParam(d, parseParamValue(d, text));
  throw usageError(fmt::format("unknown parameter '{}' for projection {} and filter {} (penumbra list shows them all)", key,
                               mTechnique.projection(), mTechnique.filter()));
}

void ViewSession::render(int width, int height, int litView) {
  mRenderer.setCameraAndLights(mScene.camera, mScene.lights);
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.debugView = litView;
  options.cameraCut = std::exchange(mCameraCut, false);
  mRenderer.render(options);
  mHasFrame = true;
}

}  // namespace penumbra::viewer
