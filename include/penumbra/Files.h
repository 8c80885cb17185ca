#pragma once
// Output files and the cache folder. Every writer writes to a temporary name in the same folder
// (unique per process and call) and renames, so a failed or concurrent run never leaves a
// half-written file. A symbolic link is followed (the link stays); a character device or FIFO
// (/dev/null, a pipe) is written through, never replaced; a folder, a disk or a socket is
// refused. Errors throw penumbra::Error naming the file.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

/// Writes text to a file atomically (temporary name, then rename).
void writeTextFile(const std::filesystem::path& path, std::string_view text);
/// Writes the byte blocks one after another to a file atomically (e.g. a cache's header, then
/// its payload).
void writeBinaryFile(const std::filesystem::path& path, std::initializer_list<std::span<const char>> blocks);
void writeBinaryFile(const std::filesystem::path& path, std::span<const std::span<const char>> blocks);

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

// --- a bounded cache folder -------------------------------------------------------------
// A cache folder holds entries named <kind>-<16 hex digits>.bin (reference-…, sdf-…), and while
// one is written its temporary file (the name + ".tmp.<pid>.<n>"); anything else in it is not an
// entry and is never counted, moved or removed. A temporary whose process is gone (killed during
// the write) is an entry too, an interrupted one: counted, listed and removed first. Its size is
// capped: after each write the least recently used entries go until the rest fit. "Used" is the
// entry's modification time, set when it is written and again whenever it is read
// (touchCacheEntry).

/// Cap of the cache folder when nothing else says: 4 GiB, a few hundred references at 1280×720
/// (33 bytes a pixel) or thousands at the bench's 256×144.
inline constexpr std::uintmax_t kDefaultCacheMaxMiB = 4096;
/// The environment variable that sets the cap, in MiB (a whole number ≥ 0; 0 keeps nothing).
inline constexpr const char* kCacheMaxEnv = "PENUMBRA_CACHE_MAX_MB";

/// $PENUMBRA_CACHE_MAX_MB in bytes if set, else kDefaultCacheMaxMiB. Throws a usage Error when
/// the variable is not a whole number of MiB.
std::uintmax_t defaultCacheMaxBytes();

struct CacheEntry {
  std::filesystem::path path;
  std::uintmax_t bytes = 0;
  std::filesystem::file_time_type lastUse;  ///< its modification time
  bool interrupted = false;  ///< the temporary file of a write whose process is gone
};

/// Throws penumbra::Error naming `dir` when it cannot be a cache folder: it is a file, or a
/// symbolic link to nothing. A folder not made yet is fine (the first write makes it).
void checkCacheFolder(const std::filesystem::path& dir);
/// The folder's entries, interrupted writes first, then least recently used first (an empty list
/// when the folder is missing).
std::vector<CacheEntry> listCacheEntries(const std::filesystem::path& dir);
/// Marks an entry as just used. A failure (a read-only folder) is ignored: reading still works.
void touchCacheEntry(const std::filesystem::path& entry);
/// Removes entries in listCacheEntries' order until the rest total at most maxBytes; returns
/// those removed. An entry that another process removed first is skipped; one that cannot be
/// removed (a read-only folder) stays, and `failures`, when given, gets "name: why" for it.
std::vector<CacheEntry> trimCache(const std::filesystem::path& dir, std::uintmax_t maxBytes,
                                  std::vector<std::string>* failures = nullptr);

}  // namespace penumbra
