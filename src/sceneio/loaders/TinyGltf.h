#pragma once
// tinygltf as Penumbra configures it, for every loader file: declarations only here;
// GltfLoader.cpp defines TINYGLTF_IMPLEMENTATION before including this, once.
#define TINYGLTF_NO_STB_IMAGE        // GltfTextures.cpp decodes images, size limits first
#define TINYGLTF_NO_STB_IMAGE_WRITE  // Penumbra never writes glTF
#include <tiny_gltf.h>
