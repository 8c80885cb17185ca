#pragma once
// "Save settings": the viewer's current scene, camera, light and technique written as a scene
// file in the JSON format that loadSceneFile() reads (src/scene/SceneFile.cpp), so that
// `penumbra render --scene saved.json` reproduces what the viewer shows.
#include <penumbra/Scene.h>
#include <penumbra/Technique.h>

#include <filesystem>
#include <string>

namespace penumbra::viewer {

/// The scene file text. Objects are copied from the scene's own file when it has one (so any
/// key this writer does not know survives); otherwise each object is written from its mesh,
/// recognised by Mesh::name as one of the file format's shapes (plane, box, sphere, cylinder,
/// cone) with sizes from its bounds and its transform as translate/rotateDeg/scale.
/// The technique's ids and map size go into "shadow", every parameter of its projection and
/// filter into shadow.params.
/// Throws Error for an object whose mesh has no scene-file form, or a shear in a transform.
std::string sceneFileText(const Scene& scene, const Technique& technique);

/// Writes sceneFileText() to `path` (atomically) and loads it back with loadSceneFile() to
/// prove it reads; throws Error naming the file otherwise.
void saveSceneFile(const std::filesystem::path& path, const Scene& scene, const Technique& technique);

/// Splits a transform into the file format's translate · Ry · Rx · Rz · scale (degrees).
/// Throws Error if the matrix has a shear or a zero scale (not expressible).
struct Trs {
  glm::vec3 translate{0.0f}, rotateDeg{0.0f}, scale{1.0f};
};
Trs decomposeTransform(const glm::mat4& worldFromObject);

}  // namespace penumbra::viewer
