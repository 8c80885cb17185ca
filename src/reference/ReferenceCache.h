#pragma once
// The on-disk cache of reference results: one file per key, "<dir>/reference-<key>.bin", in the
// format every cache entry has (base/CacheRecord.h). Files are written to a unique temporary name
// and renamed, so a reader never sees half a file; a file that fails any check (size, magic, kind,
// version, key, the hash of every other byte, each block's size) is ignored.
#include <penumbra/Reference.h>

#include <cstdint>
#include <filesystem>
#include <optional>

namespace penumbra::reference {

/// ReferenceResult::horizonPixels of a result's arrays: pixels outside litMask with light on them
/// (shadingExact ≠ 0). Derived, not stored: a traced result and its cached copy count alike.
size_t countHorizonPixels(const ReferenceResult& result);

std::filesystem::path cacheFilePath(const std::filesystem::path& dir, uint64_t key);

/// Creates `dir` if needed. Throws penumbra::Error naming it and why when it cannot be created
/// (the trace then goes on without the cache: ReferenceResult::cacheWarning).
void prepareCacheDir(const std::filesystem::path& dir);

/// The result stored under `key`, or nothing when there is none or it is unreadable or corrupt.
std::optional<ReferenceResult> loadCachedResult(const std::filesystem::path& dir, uint64_t key);

/// Stores `result` under result.cacheKey. Throws penumbra::Error naming the file on I/O failure.
void storeCachedResult(const std::filesystem::path& dir, const ReferenceResult& result);

}  // namespace penumbra::reference
