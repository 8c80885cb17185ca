#pragma once
// One-channel 32-bit float EXR files (OpenEXR): exact values for other tools. Writers are atomic
// like every output file (penumbra/Files.h). Errors throw penumbra::Error naming the file.
#include <filesystem>
#include <span>
#include <vector>

namespace penumbra {

/// One-channel 32-bit float EXR (channel "V" unless named); row 0 = top.
void writeExr(const std::filesystem::path& path, int width, int height, std::span<const float> values,
              const char* channel = "V");
/// Reads a one-channel float EXR written by writeExr.
std::vector<float> readExr(const std::filesystem::path& path, int& width, int& height);

}  // namespace penumbra
