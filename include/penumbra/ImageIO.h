#pragma once
// Image and other output files. Every writer writes to a temporary name in the same folder
// (unique per process and call) and renames, so a failed or concurrent run never leaves a
// half-written file. Errors throw penumbra::Error naming the file.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string_view>
#include <algorithm>
#include <vector>

namespace penumbra {

/// 8-bit RGBA PNG; `rgba` has width*height*4 bytes, row 0 = top.
void writePng(const std::filesystem::path& path, int width, int height, std::span<const uint8_t> rgba);
/// One-channel 32-bit float EXR (channel "V" unless named); row 0 = top.
void writeExr(const std::filesystem::path& path, int width, int height, std::span<const float> values,
              const char* channel = "V");
/// Reads a PNG as RGBA8 (row 0 = top).
std::vector<uint8_t> readPng(const std::filesystem::path& path, int& width, int& height);
/// Reads a one-channel float EXR written by writeExr.
std::vector<float> readExr(const std::filesystem::path& path, int& width, int& height);

/// Flips rows (GL's bottom-up order ↔ image files' top-down order).
template <class T>
std::vector<T> flipRows(std::span<const T> pixels, int width, int height, int channels = 1) {
  std::vector<T> out(pixels.size());
  const size_t row = static_cast<size_t>(width) * static_cast<size_t>(channels);
  for (int y = 0; y < height; ++y)
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(y) * row), row,
                out.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(height - 1 - y) * row));
  return out;
}

/// Writes text to a file atomically (temporary name, then rename).
void writeTextFile(const std::filesystem::path& path, std::string_view text);
/// Writes the byte blocks one after another to a file atomically (e.g. a cache's header, then
/// its payload).
void writeBinaryFile(const std::filesystem::path& path, std::initializer_list<std::span<const char>> blocks);

}  // namespace penumbra
