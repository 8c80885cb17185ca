#pragma once
// Output files and the cache folder. Every writer writes to a temporary name in the same folder
// (unique per process and call) and renames, so a failed or concurrent run never leaves a
// half-written file. Errors throw penumbra::Error naming the file.
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string_view>

namespace penumbra {

/// Writes text to a file atomically (temporary name, then rename).
void writeTextFile(const std::filesystem::path& path, std::string_view text);
/// Writes the byte blocks one after another to a file atomically (e.g. a cache's header, then
/// its payload).
void writeBinaryFile(const std::filesystem::path& path, std::initializer_list<std::span<const char>> blocks);

/// Where Penumbra keeps what it can recompute (references, distance fields): $PENUMBRA_CACHE if
/// set, else $XDG_CACHE_HOME/penumbra, else ~/.cache/penumbra; empty when none of these can be
/// formed (no HOME).
std::filesystem::path defaultCacheDir();

}  // namespace penumbra
