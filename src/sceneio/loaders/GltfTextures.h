#pragma once
// glTF textures as Penumbra reads them (GltfTextures.cpp): images kept encoded while tinygltf
// parses and decoded (PNG, JPEG; size-limited) only when a base-colour texture uses them, and
// KHR_texture_transform folded into the texture coordinates.
#include "sceneio/loaders/ModelImport.h"

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include <optional>
#include <string>

namespace tinygltf {
class Image;
struct TextureInfo;
}  // namespace tinygltf

namespace penumbra::loaders {

/// tinygltf's image callback (its LoadImageDataFunction, user data unused): keeps the encoded
/// bytes as they are. A normal map in WebP or an image no material uses then costs nothing.
bool keepEncodedImage(tinygltf::Image* image, int index, std::string* err, std::string* warn, int, int,
                      const unsigned char* bytes, int size, void* user);

/// Decodes image `index` of the document (kept by keepEncodedImage) to RGBA8, after checking its
/// header against kMaxImageSide and `decodedBytes` (the running total) against kMaxImageBytes.
/// Throws Error naming `field` (the texture that uses it) and the image.
Image decodeImage(const tinygltf::Image& image, int index, const std::string& file, const std::string& field,
                  uint64_t& decodedBytes);

/// A texture's KHR_texture_transform: uv' = offset + rotation(θ) · (scale ⊙ uv), and the
/// texture-coordinate set it may override. Identity when the extension is absent.
struct UvTransform {
  glm::mat3 matrix{1.0f};
  std::optional<int> texCoord;
  glm::vec2 apply(glm::vec2 uv) const { return glm::vec2(matrix * glm::vec3(uv, 1.0f)); }
};

/// Reads `info`'s KHR_texture_transform; throws Error naming `field` + ".extensions.…" for a
/// value that is not a finite number (or a non-negative texCoord).
UvTransform readTextureTransform(const tinygltf::TextureInfo& info, const std::string& file, const std::string& field);

}  // namespace penumbra::loaders
