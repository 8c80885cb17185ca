// Keyframe evaluation and posing a scene at a time (penumbra/Animation.h).
#include <penumbra/Animation.h>
#include <penumbra/Scene.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace penumbra {
namespace {

// A rotation key's quaternion may be off unit length by float rounding of a file's numbers.
constexpr float kUnitQuaternionTolerance = 1e-3f;

glm::vec3 mix(const glm::vec3& a, const glm::vec3& b, float f) { return a + (b - a) * f; }
float mix(float a, float b, float f) { return a + (b - a) * f; }
glm::quat mix(const glm::quat& a, const glm::quat& b, float f) {
  // Shortest arc: q and -q are the same rotation.
  return glm::normalize(glm::slerp(a, glm::dot(a, b) < 0.0f ? -b : b, f));
}

template <class T>
std::string keysProblem(const Keys<T>& k, const std::string& what) {
  if (k.timesS.size() != k.values.size())
    return fmt::format("{}: {} key times for {} values", what, k.timesS.size(), k.values.size());
  for (size_t i = 0; i < k.timesS.size(); ++i) {
    if (!std::isfinite(k.timesS[i])) return fmt::format("{}: key time {} is not finite", what, i);
    if (i > 0 && !(k.timesS[i] > k.timesS[i - 1]))
      return fmt::format("{}: key times must increase ({} s after {} s)", what, k.timesS[i], k.timesS[i - 1]);
  }
  return "";
}

std::string trackProblem(const TransformTrack& t, const std::string& what) {
  for (const std::string& p : {keysProblem(t.translationKeys, what + " translation"), keysProblem(t.rotationKeys, what + " rotation"),
                               keysProblem(t.scaleKeys, what + " scale")})
    if (!p.empty()) return p;
  for (const glm::quat& q : t.rotationKeys.values)
    if (!(std::abs(glm::length(q) - 1.0f) < kUnitQuaternionTolerance)) return what + " rotation: a key is not a unit quaternion";
  if (t.fixed && t.animated()) return what + ": a matrix transform cannot be keyed";
  return "";
}

template <class T>
float lastTime(const Keys<T>& k) { return k.empty() ? 0.0f : k.timesS.back(); }

float lastTime(const TransformTrack& t) {
  return std::max({lastTime(t.translationKeys), lastTime(t.rotationKeys), lastTime(t.scaleKeys)});
}

}  // namespace

template <class T>
T Keys<T>::at(float timeS) const {
  if (timeS <= timesS.front()) return values.front();
  if (timeS >= timesS.back()) return values.back();
  const size_t next = static_cast<size_t>(std::upper_bound(timesS.begin(), timesS.end(), timeS) - timesS.begin());
  const size_t prev = next - 1;
  if (interpolation == Interpolation::Step) return values[prev];
  const float f = (timeS - timesS[prev]) / (timesS[next] - timesS[prev]);
  return mix(values[prev], values[next], f);
}

template struct Keys<glm::vec3>;
template struct Keys<glm::quat>;
template struct Keys<float>;

glm::mat4 TransformTrack::matrixAt(float timeS) const {
  if (fixed) return *fixed;
  const glm::vec3 t = translationKeys.empty() ? translation : translationKeys.at(timeS);
  const glm::quat r = rotationKeys.empty() ? rotation : rotationKeys.at(timeS);
  const glm::vec3 s = scaleKeys.empty() ? scale : scaleKeys.at(timeS);
  return glm::scale(glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r), s);
}

glm::vec3 sunDirection(float azimuthDeg, float elevationDeg) {
  const float a = glm::radians(azimuthDeg), e = glm::radians(elevationDeg);
  return -glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
}

float SceneAnimation::durationS() const {
  float d = std::max(lastTime(camera.position), lastTime(camera.target));
  for (const AnimatedNode& n : nodes) d = std::max(d, lastTime(n.track));
  for (const LightAnimation& l : lights) d = std::max(d, lastTime(l.track));
  for (const SunPath& s : suns) d = std::max({d, lastTime(s.azimuthDeg), lastTime(s.elevationDeg)});
  return d;
}

void SceneAnimation::removeLight(uint32_t index) {
  const auto renumber = [index](auto& list) {
    std::erase_if(list, [index](const auto& entry) { return entry.light == index; });
    for (auto& entry : list)
      if (entry.light > index) --entry.light;
  };
  renumber(lights);
  renumber(suns);
}

std::vector<bool> SceneAnimation::movingObjects(size_t objectCount) const {
  std::vector<bool> nodeMoves(nodes.size(), false);
  for (size_t i = 0; i < nodes.size(); ++i)
    nodeMoves[i] = nodes[i].track.animated() || (nodes[i].parent >= 0 && nodeMoves[static_cast<size_t>(nodes[i].parent)]);
  std::vector<bool> moving(objectCount, false);
  for (const ObjectAnimation& o : objects)
    if (o.object < objectCount && o.node < nodes.size() && nodeMoves[o.node]) moving[o.object] = true;
  return moving;
}

std::string SceneAnimation::problem(size_t objectCount, size_t lightCount) const {
  for (size_t i = 0; i < nodes.size(); ++i) {
    const std::string what = fmt::format("animation node {} ('{}')", i, nodes[i].name);
    if (nodes[i].parent >= static_cast<int>(i) || nodes[i].parent < -1) return what + ": its parent is not an earlier node";
    if (std::string p = trackProblem(nodes[i].track, what); !p.empty()) return p;
  }
  for (const ObjectAnimation& o : objects)
    if (o.object >= objectCount || o.node >= nodes.size())
      return fmt::format("an object animation names object {} of {} and node {} of {}", o.object, objectCount, o.node, nodes.size());
  for (const LightAnimation& l : lights) {
    if (l.light >= lightCount) return fmt::format("a light animation names light {} of {}", l.light, lightCount);
    if (l.node >= static_cast<int>(nodes.size()))
      return fmt::format("light {} animation names node {} of {}", l.light, l.node, nodes.size());
    if (std::string p = trackProblem(l.track, fmt::format("light {} animation", l.light)); !p.empty()) return p;
  }
  for (const SunPath& s : suns) {
    const std::string what = fmt::format("light {} sun path", s.light);
    if (s.light >= lightCount) return fmt::format("a sun path names light {} of {}", s.light, lightCount);
    if (s.azimuthDeg.empty() || s.azimuthDeg.timesS != s.elevationDeg.timesS) return what + ": azimuth and elevation need the same key times";
    if (std::string p = keysProblem(s.azimuthDeg, what); !p.empty()) return p;
  }
  for (const std::string& p : {keysProblem(camera.position, "camera position"), keysProblem(camera.target, "camera target")})
    if (!p.empty()) return p;
  if (camera.node >= static_cast<int>(nodes.size())) return fmt::format("the camera animation names node {} of {}", camera.node, nodes.size());
  if (camera.node >= 0 && !(camera.position.empty() && camera.target.empty()))
    return "the camera follows a node and keys: one or the other";
  return "";
}

namespace {

/// Every node's world transform at `timeS` (parents come before their children).
std::vector<glm::mat4> nodeWorlds(const SceneAnimation& a, float timeS) {
  std::vector<glm::mat4> world(a.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const AnimatedNode& n = a.nodes[i];
    const glm::mat4 parent = n.parent >= 0 ? world[static_cast<size_t>(n.parent)] : glm::mat4(1.0f);
    world[i] = parent * n.offset * n.track.matrixAt(timeS);
  }
  return world;
}

/// An animated light's transform at `timeS`: its node's, or its track about its pivot.
glm::mat4 lightTransform(const LightAnimation& la, const std::vector<glm::mat4>& world, float timeS) {
  return la.node >= 0 ? world[static_cast<size_t>(la.node)]
                      : glm::translate(glm::mat4(1.0f), la.pivot) * la.track.matrixAt(timeS) * glm::translate(glm::mat4(1.0f), -la.pivot);
}

/// Poses `camera` (position, target, up in a node) at `timeS`.
void poseCamera(Camera& camera, const CameraAnimation& c, const std::vector<glm::mat4>& world, float timeS) {
  if (c.node >= 0) {
    const glm::mat4& m = world[static_cast<size_t>(c.node)];
    const glm::vec3 forward = glm::mat3(m) * glm::vec3(0.0f, 0.0f, -1.0f), up = glm::mat3(m) * glm::vec3(0.0f, 1.0f, 0.0f);
    if (glm::length(forward) > 0.0f && glm::length(up) > 0.0f) {  // a node scaled to 0 leaves the camera be
      camera.position = glm::vec3(m[3]);
      camera.target = camera.position + glm::normalize(forward);
      camera.up = glm::normalize(up);
    }
  }
  if (!c.position.empty()) camera.position = c.position.at(timeS);
  if (!c.target.empty()) camera.target = c.target.at(timeS);
}

bool withinWorld(const glm::vec3& p) { return glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(kMaxCoordinateM))); }

// Most times poseProblem checks: a scene's key times beyond it are sampled evenly (first and last
// kept), so that a glTF of many keys and objects is checked in a fraction of a second.
constexpr size_t kMaxCheckedTimes = 4096;

}  // namespace

std::vector<float> SceneAnimation::keyTimes() const {
  std::vector<float> t;
  const auto add = [&](const auto& keys) { t.insert(t.end(), keys.timesS.begin(), keys.timesS.end()); };
  const auto addTrack = [&](const TransformTrack& track) {
    add(track.translationKeys);
    add(track.rotationKeys);
    add(track.scaleKeys);
  };
  for (const AnimatedNode& n : nodes) addTrack(n.track);
  for (const LightAnimation& l : lights) addTrack(l.track);
  for (const SunPath& s : suns) add(s.azimuthDeg);
  add(camera.position);
  add(camera.target);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

std::string poseProblem(const Scene& scene, std::span<const float> timesS) {
  const SceneAnimation& a = scene.animation;
  if (a.empty() || timesS.empty()) return "";
  std::vector<float> times(timesS.begin(), timesS.end());
  if (times.size() > kMaxCheckedTimes) {
    std::vector<float> sampled;
    for (size_t i = 0; i < kMaxCheckedTimes; ++i) sampled.push_back(times[i * (times.size() - 1) / (kMaxCheckedTimes - 1)]);
    times = std::move(sampled);
  }
  std::vector<std::optional<Aabb>> meshBounds(scene.meshes.size());  // of the meshes animated objects use
  for (const ObjectAnimation& o : a.objects) {
    const uint32_t mesh = scene.objects[o.object].mesh;
    if (!meshBounds[mesh]) meshBounds[mesh] = scene.meshes[mesh].bounds();
  }
  for (const float t : times) {
    const std::vector<glm::mat4> world = nodeWorlds(a, t);
    for (const ObjectAnimation& o : a.objects) {
      const Object& object = scene.objects[o.object];
      const Aabb b = meshBounds[object.mesh]->transformed(world[o.node] * o.nodeFromObject);
      if (b.empty()) continue;
      for (const glm::vec3& c : {b.lo, b.hi})
        for (int i = 0; i < 3; ++i)
          if (!(std::abs(c[i]) <= kMaxCoordinateM))
            return fmt::format("at {} s: {}: world-space coordinate {} is not finite or beyond ±{} m", t, object.name, c[i], kMaxCoordinateM);
    }
    for (const LightAnimation& la : a.lights) {
      const glm::vec3 p = glm::vec3(lightTransform(la, world, t) * glm::vec4(la.restPosition, 1.0f));
      if (isPositional(scene.lights[la.light]) && !withinWorld(p))
        return fmt::format("at {} s: lights[{}]: its position ({}, {}, {}) is not finite or beyond ±{} m", t, la.light, p.x, p.y, p.z,
                           kMaxCoordinateM);
    }
    Camera camera = scene.camera;
    poseCamera(camera, a.camera, world, t);
    if (!withinWorld(camera.position) || !withinWorld(camera.target))
      return fmt::format("at {} s: camera: its position or target is beyond ±{} m", t, kMaxCoordinateM);
    if (const std::string problem = camera.viewProblem(); !problem.empty()) return fmt::format("at {} s: camera: {}", t, problem);
  }
  return "";
}

void poseScene(Scene& scene, float timeS) {
  const SceneAnimation& a = scene.animation;
  if (a.empty()) return;
  const std::vector<glm::mat4> world = nodeWorlds(a, timeS);
  for (const ObjectAnimation& o : a.objects) scene.objects[o.object].worldFromObject = world[o.node] * o.nodeFromObject;
  for (const LightAnimation& la : a.lights) {
    const glm::mat4 m = lightTransform(la, world, timeS);
    Light& l = scene.lights[la.light];
    l.position = glm::vec3(m * glm::vec4(la.restPosition, 1.0f));
    const glm::vec3 d = glm::mat3(m) * la.restDirection;
    if (glm::length(d) > 0.0f) l.direction = glm::normalize(d);
  }
  for (const SunPath& s : a.suns)
    scene.lights[s.light].direction = sunDirection(s.azimuthDeg.at(timeS), s.elevationDeg.at(timeS));
  poseCamera(scene.camera, a.camera, world, timeS);
}

}  // namespace penumbra
