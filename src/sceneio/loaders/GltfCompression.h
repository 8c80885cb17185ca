#pragma once
// Compressed glTF geometry (GltfCompression.cpp): KHR_draco_mesh_compression primitives, decoded
// by Google's Draco library, and EXT_meshopt_compression buffer views, decoded by meshoptimizer.
// Both are decoded into plain buffers, views and accessors of the tinygltf model before the
// converter runs, so every check the converter makes (indices, counts, finite values, limits)
// applies to the decoded data as to any other.
//
// tinygltf cannot parse either as written: a Draco primitive's indices accessor has no buffer
// view (tinygltf refuses it: "accessor[0] invalid bufferView"), and meshopt's fallback buffer has
// no data (no uri). prepareCompressed() notes both and takes them out of the JSON first;
// decompress() puts the decoded data in after tinygltf has loaded the buffers.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf { class Model; }

namespace penumbra::loaders {

/// Decoded data, all compressed parts of one file together: like the file size limit, it keeps a
/// crafted file from asking for unbounded memory.
inline constexpr uint64_t kMaxDecompressedBytes = uint64_t(1) << 30;

struct DracoPrimitive {
  size_t mesh = 0, primitive = 0;
  uint64_t bufferView = 0;
  std::vector<std::pair<std::string, uint64_t>> attributes;  ///< glTF attribute name → Draco unique id
  int64_t indices = -1;  ///< the indices accessor tinygltf was not shown (-1: none)
};

struct MeshoptView {
  size_t view = 0;
  uint64_t buffer = 0, byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter;  ///< ATTRIBUTES | TRIANGLES | INDICES; NONE | OCTAHEDRAL | QUATERNION | EXPONENTIAL
};

/// What decompress() must do, from the JSON.
struct CompressedParts {
  std::vector<DracoPrimitive> draco;
  std::vector<MeshoptView> meshopt;
  bool rewritten = false;  ///< the JSON was changed: tinygltf must parse doc.dump()
};

/// Reads (and checks, naming the field) every Draco primitive and meshopt view of `doc`, and
/// rewrites what tinygltf cannot parse: a Draco primitive's indices are hidden, a meshopt
/// fallback buffer without data gets one placeholder byte.
CompressedParts prepareCompressed(nlohmann::json& doc, const std::string& file);

/// Decodes every part into new buffers, views and accessors of `model` (loaded by tinygltf from
/// the prepared JSON). Throws Error naming the file and the field on data the decoders refuse.
void decompress(tinygltf::Model& model, const CompressedParts& parts, const std::string& file);

}  // namespace penumbra::loaders
