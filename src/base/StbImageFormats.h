#pragma once
// The image formats stb_image decodes in Penumbra: PNG only (its own files, glTF textures).
// JPEG goes through libjpeg-turbo (scene/loaders/GltfTextures.cpp): Debian 12's stb_image
// (2022-09) decodes crafted JPEGs with memory errors (an out-of-bounds write in its Huffman table
// builder, out-of-bounds reads, crashes: found within minutes by fuzzing, fixed upstream in 2.28).
// Included before stb_image.h wherever its implementation is compiled (base/ImageIO.cpp; the fuzz
// target, tests/loaders), so both decode the same formats.
#define STBI_ONLY_PNG
