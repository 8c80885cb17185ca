// glTF 2.0 animations (§3.11): samplers of key times (input, SCALAR float) and values (output:
// VEC3 for translation and scale, VEC4 for rotation), LINEAR or STEP; CUBICSPLINE keys keep their
// values and drop their tangents (played linearly).
#include "sceneio/loaders/GltfAnimation.h"

#include "sceneio/loaders/ModelImport.h"
#include "sceneio/loaders/TinyGltf.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra::loaders {
namespace {

// CUBICSPLINE outputs hold (in-tangent, value, out-tangent) per key.
constexpr size_t kCubicElementsPerKey = 3;
constexpr size_t kCubicValueElement = 1;

template <class T>
void fill(Keys<T>& keys, const std::vector<float>& times, const std::vector<float>& values, size_t components, size_t perKey,
          Interpolation interpolation) {
  keys.timesS = times;
  keys.interpolation = interpolation;
  for (size_t k = 0; k < times.size(); ++k) {
    const float* v = values.data() + (k * perKey + (perKey == 1 ? 0 : kCubicValueElement)) * components;
    if constexpr (std::is_same_v<T, glm::quat>) keys.values.push_back(glm::normalize(glm::quat(v[3], v[0], v[1], v[2])));
    else keys.values.push_back(T(v[0], v[1], v[2]));
  }
}

}  // namespace

std::map<int, TransformTrack> readGltfAnimations(const tinygltf::Model& g, const std::string& file, const ReadFloats& read) {
  std::map<int, TransformTrack> tracks;
  for (size_t ai = 0; ai < g.animations.size(); ++ai) {
    const tinygltf::Animation& a = g.animations[ai];
    for (size_t ci = 0; ci < a.channels.size(); ++ci) {
      const tinygltf::AnimationChannel& c = a.channels[ci];
      const std::string field = fmt::format("animations[{}].channels[{}]", ai, ci);
      if (c.target_path == "weights") continue;  // morph targets are not supported
      if (c.target_node < 0) continue;            // no target: an extension's channel
      if (static_cast<size_t>(c.target_node) >= g.nodes.size())
        fail(file, field + ".target.node", fmt::format("no node {} ({} nodes)", c.target_node, g.nodes.size()));
      if (c.sampler < 0 || static_cast<size_t>(c.sampler) >= a.samplers.size())
        fail(file, field + ".sampler", fmt::format("no sampler {} ({} samplers)", c.sampler, a.samplers.size()));
      const tinygltf::AnimationSampler& s = a.samplers[static_cast<size_t>(c.sampler)];
      const std::string sf = fmt::format("animations[{}].samplers[{}]", ai, c.sampler);
      Interpolation interpolation = Interpolation::Linear;
      size_t perKey = 1;
      if (s.interpolation == "STEP") interpolation = Interpolation::Step;
      else if (s.interpolation == "CUBICSPLINE") perKey = kCubicElementsPerKey;
      else if (s.interpolation != "LINEAR") fail(file, sf + ".interpolation", fmt::format("'{}' is not LINEAR, STEP or CUBICSPLINE", s.interpolation));
      const std::vector<float> times = read(s.input, TINYGLTF_TYPE_SCALAR, sf + ".input");
      for (size_t k = 0; k < times.size(); ++k)
        if (!std::isfinite(times[k]) || (k > 0 && !(times[k] > times[k - 1])))
          fail(file, sf + ".input", fmt::format("key time {} ({}) is not finite or not after the one before", k, times[k]));
      const bool rotation = c.target_path == "rotation";
      if (!rotation && c.target_path != "translation" && c.target_path != "scale")
        fail(file, field + ".target.path", fmt::format("'{}' is not translation, rotation, scale or weights", c.target_path));
      const size_t components = rotation ? 4 : 3;
      const std::vector<float> values = read(s.output, rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, sf + ".output");
      if (values.size() != times.size() * perKey * components)
        fail(file, sf + ".output", fmt::format("{} values for {} key times", values.size() / components, times.size()));
      for (float v : values)
        if (!std::isfinite(v)) fail(file, sf + ".output", "a value is not finite");
      TransformTrack& t = tracks[c.target_node];
      const auto keyedTwice = [&] { fail(file, field, fmt::format("node {}'s {} is keyed by two channels", c.target_node, c.target_path)); };
      if (rotation) {
        if (!t.rotationKeys.empty()) keyedTwice();
        for (size_t k = 0; k < times.size(); ++k) {
          const float* q = values.data() + (k * perKey + (perKey == 1 ? 0 : kCubicValueElement)) * components;
          if (!(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) > 1e-6f))
            fail(file, sf + ".output", fmt::format("key {} is not a rotation (zero quaternion)", k));
        }
        fill(t.rotationKeys, times, values, components, perKey, interpolation);
      } else {
        Vec3Keys& keys = c.target_path == "translation" ? t.translationKeys : t.scaleKeys;
        if (!keys.empty()) keyedTwice();
        fill(keys, times, values, components, perKey, interpolation);
      }
    }
  }
  return tracks;
}

AnimatedNode makeAnimatedNode(const tinygltf::Node& n, const TransformTrack* keyed, const glm::mat4& local, const std::string& file,
                              const std::string& field) {
  AnimatedNode a;
  a.name = n.name.empty() ? field : n.name;
  if (keyed) a.track = *keyed;
  if (!n.matrix.empty()) {
    if (a.track.animated()) fail(file, field + ".matrix", "an animated node must give translation, rotation and scale, not a matrix");
    a.track.fixed = local;
    return a;
  }
  // `local` has checked the values.
  if (!n.translation.empty()) a.track.translation = glm::vec3(local[3]);
  if (!n.rotation.empty())
    a.track.rotation = glm::normalize(glm::quat(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                                                static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2])));
  if (!n.scale.empty()) a.track.scale = glm::vec3(n.scale[0], n.scale[1], n.scale[2]);
  return a;
}

}  // namespace penumbra::loaders
