#include "viewer/ViewSession.h"

#include "viewer/LightEdit.h"

#include <penumbra/Animation.h>
#include <penumbra/Error.h>
#include <penumbra/Registry.h>
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
void applySceneLightParams(Scene& scene, Projection& projection, Filter& filter) {
  std::vector<std::pair<std::string, std::string>> light;
  for (const auto& kv : scene.shadow.params)
    if (prefixOf(kv.first) == "light") light.push_back(kv);
  applyParams(light, scene, projection, filter);
}

}  // namespace

ViewSession::ViewSession(gl::Context& /*current: the renderer draws on it*/, Scene scene, std::unique_ptr<Projection> projection,
                         std::unique_ptr<Filter> filter, int shadowMapSize)
    : mScene(std::move(scene)), mProjectionId(projection->id()), mFilterId(filter->id()),
      mShadowMapSize(shadowMapSize) {
  // What the command line set (and the scene's own values) is remembered like a widget edit.
  for (const Parameterized* p : {static_cast<const Parameterized*>(projection.get()), static_cast<const Parameterized*>(filter.get())})
    for (const ParamDesc& d : p->paramDescs())
      if (p->param(d.key) != d.def) mRemembered[std::string(d.key)] = p->param(d.key);
  mRenderer.setScene(mScene);
  mRenderer.setTechnique(std::move(projection), std::move(filter));
}

void ViewSession::setShadowMapSize(int texels) {
  if (texels < 16) throw usageError(fmt::format("shadow map size {}: must be at least 16", texels));
  mShadowMapSize = texels;
  ++mVersion;
}

Light& ViewSession::light() {
  PN_CHECK(mSelected < mScene.lights.size(), "the scene has no light");
  ++mVersion;
  return mScene.lights[mSelected];
}

void ViewSession::checkLight(const Light& light, const std::string& which) {
  if (const std::string problem = lightProblem(light); !problem.empty()) throw usageError(fmt::format("{}: {}", which, problem));
  Renderer& r = mRenderer;
  if (const std::string why = r.projection().incompatibility(light); !why.empty())
    throw usageError(fmt::format("{}: --projection {} cannot shadow it: {}", which, mProjectionId, why));
  if (const std::string why = r.filter().incompatibility(mProjectionId, light); !why.empty())
    throw usageError(fmt::format("{}: --filter {} with --projection {} cannot shadow it: {}", which, mFilterId, mProjectionId, why));
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
  mScene.lights[index] = light;
  ++mVersion;
}

size_t ViewSession::shownLight() const {
  const size_t count = mRenderer.lightCount();
  return count == 0 ? 0 : std::min(mSelected, count - 1);
}

std::vector<DebugImage> ViewSession::debugImages() const { return mRenderer.debugImages(shownLight()); }

void ViewSession::applyRemembered(Parameterized& p) const {
  for (const ParamDesc& d : p.paramDescs())
    if (auto it = mRemembered.find(d.key); it != mRemembered.end()) p.setParam(d.key, it->second);
}

void ViewSession::rebuildTechnique(const std::string& projectionId, const std::string& filterId) {
  std::unique_ptr<Projection> projection = makeProjection(projectionId);
  std::unique_ptr<Filter> filter = makeFilter(filterId);
  for (const auto& [key, value] : mScene.shadow.params) {
    const std::string prefix = prefixOf(key);
    if (prefix == projection->id()) projection->setParam(key, std::string_view(value));
    if (prefix == filter->id()) filter->setParam(key, std::string_view(value));
  }
  applyRemembered(*projection);
  applyRemembered(*filter);
  // The renderer checks the pair against light 0; the others are checked here.
  for (size_t i = 1; i < mScene.lights.size(); ++i) {
    const Light& l = mScene.lights[i];
    if (const std::string why = projection->incompatibility(l); !why.empty())
      throw usageError(fmt::format("--projection {} is not supported for {}: {}", projectionId, lightLabel(l, i), why));
    if (const std::string why = filter->incompatibility(projectionId, l); !why.empty())
      throw usageError(fmt::format("{}: --filter {} with --projection {} is not supported: {}", lightLabel(l, i), filterId, projectionId, why));
  }
  mRenderer.setTechnique(std::move(projection), std::move(filter));  // throws before changing anything
  mProjectionId = projectionId;
  mFilterId = filterId;
  ++mVersion;
}

void ViewSession::setProjection(const std::string& id) { rebuildTechnique(id, mFilterId); }
void ViewSession::setFilter(const std::string& id) { rebuildTechnique(mProjectionId, id); }

void ViewSession::loadScene(const std::string& nameOrPath) {
  LoadOptions options;
  options.groundUnderLoneModel = true;  // as the CLI
  Scene next = penumbra::loadScene(nameOrPath, options);
  applySceneLightParams(next, mRenderer.projection(), mRenderer.filter());
  // What the new scene's file sets explicitly wins over values remembered from before.
  auto previousRemembered = mRemembered;
  for (const auto& kv : next.shadow.params) mRemembered.erase(kv.first);
  Scene previous = std::move(mScene);
  mScene = std::move(next);
  try {
    mRenderer.setScene(mScene);
    rebuildTechnique(mProjectionId, mFilterId);
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
  Renderer& r = mRenderer;
  // light.count is the bench's: the viewer adds and removes lights one by one instead.
  static const std::vector<ParamDesc> kScene = [] {
    std::vector<ParamDesc> out;
    for (const ParamDesc& d : sceneParamDescs())
      if (d.key != "light.count") out.push_back(d);
    return out;
  }();
  std::vector<ParamGroup> groups = {{"Scene", kScene},
                                    {fmt::format("Projection: {}", mProjectionId), r.projection().paramDescs()},
                                    {fmt::format("Filter: {}", mFilterId), r.filter().paramDescs()}};
  for (const AddOnGroup& g : addOnGroups()) groups.push_back({std::string(g.label), g.params});
  return groups;
}

float ViewSession::paramValue(const ParamDesc& desc) {
  Renderer& r = mRenderer;
  if (r.projection().hasParam(desc.key)) return r.projection().param(desc.key);
  if (r.filter().hasParam(desc.key)) return r.filter().param(desc.key);
  if (r.shadows().addOns().hasParam(desc.key)) return r.shadows().addOns().param(desc.key);
  // Scene parameters have no getter of their own: light.size is the light's size.
  if (desc.key == "light.size" && !mScene.lights.empty()) return mScene.lights.front().size;
  if (auto it = mRemembered.find(desc.key); it != mRemembered.end()) return it->second;
  return desc.def;
}

void ViewSession::setParam(const ParamDesc& desc, float value) {
  checkParamValue(desc, value);
  if (isSceneParam(desc.key)) {
    applyParams({{std::string(desc.key), formatParamValue(desc, value)}}, mScene, mRenderer.projection(), mRenderer.filter());
  } else {
    if (mRenderer.projection().hasParam(desc.key)) mRenderer.projection().setParam(desc.key, value);
    else if (mRenderer.filter().hasParam(desc.key)) mRenderer.filter().setParam(desc.key, value);
    else if (mRenderer.shadows().addOns().hasParam(desc.key)) mRenderer.shadows().addOns().setParam(desc.key, value);
    else throw usageError(fmt::format("parameter '{}' belongs to neither --projection {} nor --filter {}", desc.key, mProjectionId, mFilterId));
    mRemembered[std::string(desc.key)] = value;
  }
  ++mVersion;
}

void ViewSession::setParam(const std::string& assignment) {
  const auto [key, text] = splitAssignment(assignment);
  for (const ParamGroup& g : paramGroups())
    for (const ParamDesc& d : g.descs)
      if (d.key == key) return setParam(d, parseParamValue(d, text));
  throw usageError(fmt::format("unknown parameter '{}' for --projection {} --filter {} (penumbra list shows them all)", key,
                               mProjectionId, mFilterId));
}

void ViewSession::render(int width, int height, int litView) {
  mRenderer.setCameraAndLights(mScene.camera, mScene.lights);
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.shadowMapSize = mShadowMapSize;
  options.debugView = litView;
  options.cameraCut = std::exchange(mCameraCut, false);
  mRenderer.render(options);
  mHasFrame = true;
}

}  // namespace penumbra::viewer
