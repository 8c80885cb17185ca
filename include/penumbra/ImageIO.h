#pragma once
// PNG image files. Writers are atomic like every output file (penumbra/Files.h): a failed or
// concurrent run never leaves a half-written image. Errors throw penumbra::Error naming the file.
// Float images (EXR) are in penumbra/Exr.h.
#include <penumbra/Image.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace penumbra {

/// 8-bit RGBA PNG; `rgba` has width*height*4 bytes, row 0 = top.
void writePng(const std::filesystem::path& path, int width, int height, std::span<const uint8_t> rgba);
/// Reads a PNG as RGBA8 (row 0 = top).
std::vector<uint8_t> readPng(const std::filesystem::path& path, int& width, int& height);
}  // namespace penumbra
