#include "base/AtomicFile.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace penumbra {
namespace {

std::atomic<unsigned> gTemporaryCounter{0};

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : mTarget(std::move(target)) {
  if (mTarget.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(mTarget.parent_path(), ec);
    if (ec) throw Error(fmt::format("{}: cannot create the folder ({})", mTarget.parent_path().string(), ec.message()));
  }
  // Unique per process and call: two runs (or threads) writing the same file never share one.
  mTemporary = mTarget;
  mTemporary += fmt::format(".tmp.{}.{}", getpid(), gTemporaryCounter.fetch_add(1));
}

AtomicFile::~AtomicFile() {
  if (mCommitted) return;
  std::error_code ignored;
  std::filesystem::remove(mTemporary, ignored);
}

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(mTemporary, mTarget, ec);
  if (ec) throw Error(fmt::format("{}: cannot write ({})", mTarget.string(), ec.message()));
  mCommitted = true;
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
  writeBinaryFile(path, {std::span<const char>(text.data(), text.size())});
}

void writeBinaryFile(const std::filesystem::path& path, std::initializer_list<std::span<const char>> blocks) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temporary(), std::ios::binary | std::ios::trunc);
    for (std::span<const char> b : blocks) out.write(b.data(), static_cast<std::streamsize>(b.size()));
    out.close();
    if (!out) throw Error(fmt::format("{}: cannot write", path.string()));
  }
  file.commit();
}

std::filesystem::path defaultCacheDir() {
  if (const char* dir = std::getenv("PENUMBRA_CACHE"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "penumbra";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "penumbra";
  return {};
}

}  // namespace penumbra
