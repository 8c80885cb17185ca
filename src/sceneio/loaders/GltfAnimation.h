#pragma once
// glTF animations → keyed TRS tracks per node (GltfAnimation.cpp). Every animation of the file
// plays at once, from its own time 0; channels on "weights" (morph targets) are skipped.
#include <penumbra/Animation.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace tinygltf { class Model; class Node; }

namespace penumbra::loaders {

/// Reads accessor `index` as floats (count × components, normalised integers mapped to [-1, 1]
/// or [0, 1]) after the converter's checks; `type` is TINYGLTF_TYPE_SCALAR, _VEC3 or _VEC4 and
/// `use` names the reader in errors.
using ReadFloats = std::function<std::vector<float>(int index, int type, const std::string& use)>;

/// The keyed channels of every animated node, by node index (rest values left at identity: the
/// converter fills them from the node). Throws Error("file: animations[i]…: problem") on a bad
/// sampler, a node that does not exist, key times that do not increase, or a target path that
/// is keyed twice.
std::map<int, TransformTrack> readGltfAnimations(const tinygltf::Model& model, const std::string& file, const ReadFloats& read);

/// The animation node of glTF node `n` (parent and offset left for the caller): `keyed`'s
/// channels (or none) over the node's rest translation/rotation/scale, or its `local` matrix as
/// a fixed transform. Throws Error naming `field` when a keyed node gives a matrix.
AnimatedNode makeAnimatedNode(const tinygltf::Node& n, const TransformTrack* keyed, const glm::mat4& local, const std::string& file,
                              const std::string& field);

}  // namespace penumbra::loaders
