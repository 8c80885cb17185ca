#pragma once
// The checked conversion of a parsed glTF document into a Model (GltfConverter.cpp).
#include "sceneio/loaders/ModelImport.h"

#include <string>

namespace tinygltf { class Model; }

namespace penumbra::loaders {

/// Converts a document tinygltf has parsed; `file` names it in errors. Throws Error on any index,
/// range, count or value that is out of bounds, and when the scene places no triangle. Reports
/// the meshes converted to `progress` when given.
Model convertGltf(const tinygltf::Model& model, const std::string& file, ProgressReport* progress = nullptr);

}  // namespace penumbra::loaders
