#pragma once
// Compressed glTF test models, encoded with the same libraries Penumbra decodes with (Draco,
// meshoptimizer): a box on a ground plane as plain, KHR_draco_mesh_compression and
// EXT_meshopt_compression GLB files, and broken variants. tests/tools/MakeCompressedModels.cpp
// writes them to tests/data/ (models/*_box.glb, bad/*); the unit and GL tests also build them in
// memory.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace penumbra::test {

/// The geometry every variant holds: a 1 m box standing on a 6 m ground plane (y = 0), each a
/// triangle list with normals and texture coordinates.
struct BoxGeometry {
  struct Part {
    std::vector<float> positions, normals, uvs;  ///< 3, 3, 2 floats per vertex
    std::vector<uint32_t> indices;
  };
  Part box, ground;
};
BoxGeometry boxGeometry();

/// Whole GLB files.
std::vector<uint8_t> plainBoxGlb();
std::vector<uint8_t> dracoBoxGlb();
std::vector<uint8_t> meshoptBoxGlb();

/// Broken files, by name (each must be refused with a message naming the field).
std::map<std::string, std::vector<uint8_t>> brokenCompressedFiles();

}  // namespace penumbra::test
