#pragma once
// The glTF JSON, checked before tinygltf parses it (GltfDocument.cpp). tinygltf's own messages
// name no field ("JSON string too short.", "'byteLength' property is missing"), and two of its
// paths are unsafe (its `extras` reader recurses once per nesting level; it hands an image
// straight from a buffer view that runs past its buffer to the image callback), so this pass
// checks first, naming the field: the nesting depth, that it is JSON and glTF 2.0 (glTF 1.0 is
// named and refused), that every member tinygltf requires is there with the right type, and
// every buffer view against its buffer.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>

namespace penumbra::loaders {

/// Throws Error("file: field: problem"); returns the parsed document.
nlohmann::json checkGltfDocument(const std::string& file, std::span<const uint8_t> text);

}  // namespace penumbra::loaders
