#pragma once
// Output files and the cache folder. Every writer writes to a temporary name in the same folder
// (unique per process and call) and renames, so a failed or concurrent run never leaves a
// half-written file. A symbolic link is followed (the link stays); a character device or FIFO
// (/dev/null, a pipe) is written through, never replaced; a folder, a disk or a socket is
// refused. Errors throw penumbra::Error naming the file.
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

/// Checks, before any work, that a file can be written at `path` as the writers above would:
/// the path is not empty and names no folder, disk or socket; a device or FIFO is writable;
/// otherwise its folder exists or can be created and accepts new files (a probe file is created
/// and removed there). Throws penumbra::Error naming the path. A run that checks every output
/// first never fails on a later output after writing an earlier one.
void checkOutputFile(const std::filesystem::path& path);
/// The same for an output folder: it is a folder, or can be created, and accepts new files.
void checkOutputFolder(const std::filesystem::path& path);

/// Where Penumbra keeps what it can recompute (references, distance fields): $PENUMBRA_CACHE if
/// set, else $XDG_CACHE_HOME/penumbra, else ~/.cache/penumbra; empty when none of these can be
/// formed (no HOME).
std::filesystem::path defaultCacheDir();

}  // namespace penumbra
