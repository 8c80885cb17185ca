#include "base/AtomicFile.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace penumbra {
namespace {

std::atomic<unsigned> gTemporaryCounter{0};

// Symbolic links followed before giving up: the kernel's own limit (MAXSYMLINKS, ELOOP).
constexpr int kMaxSymlinkHops = 40;
// The write-through copy moves the temporary file into the device in blocks of this size.
constexpr size_t kCopyBlockBytes = size_t(1) << 16;

std::string errnoText() { return std::strerror(errno); }

/// The longest file name (bytes) the file system at `folder` takes: 255 on Linux's own.
size_t maxNameBytes(const std::filesystem::path& folder) {
  constexpr size_t kPosixNameMax = 255;
  const long max = pathconf(folder.empty() ? "." : folder.c_str(), _PC_NAME_MAX);
  return max > 0 ? static_cast<size_t>(max) : kPosixNameMax;
}

/// The nearest existing folder at or above `folder` (where the name limit is known).
std::filesystem::path existingFolder(std::filesystem::path folder) {
  std::error_code ec;
  while (!folder.empty() && !std::filesystem::is_directory(folder, ec)) {
    if (folder == folder.parent_path()) break;
    folder = folder.parent_path();
  }
  return folder;
}

/// What a target path leads to once symbolic links are followed.
struct Destination {
  std::filesystem::path path;
  bool writeThrough = false;  ///< a character device or a FIFO: written into, never replaced
};

Destination resolve(const std::filesystem::path& target) {
  if (target.empty()) throw Error("an empty path names no file");
  if (!target.has_filename())
    throw Error(fmt::format("{}: names a folder (it ends in '/'); give a file name", target.string()));
  std::filesystem::path p = target;
  for (int hop = 0;; ++hop) {
    // Its name must fit the file system (a new file, or a link's target).
    if (const size_t bytes = p.filename().string().size(), max = maxNameBytes(existingFolder(p.parent_path())); bytes > max)
      throw Error(fmt::format("{}: the file name is {} bytes, more than the {} the file system takes; give a shorter name",
                              target.string(), bytes, max));
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0) {
      if (errno == ENOENT) return {p, false};  // a new file (its folders are created when written)
      throw Error(fmt::format("{}: cannot write there ({})", target.string(), errnoText()));
    }
    if (S_ISLNK(st.st_mode)) {
      if (hop == kMaxSymlinkHops) throw Error(fmt::format("{}: too many levels of symbolic links", target.string()));
      std::error_code ec;
      const std::filesystem::path link = std::filesystem::read_symlink(p, ec);
      if (ec) throw Error(fmt::format("{}: cannot read the symbolic link ({})", target.string(), ec.message()));
      p = link.is_absolute() ? link : p.parent_path() / link;
      continue;
    }
    if (S_ISREG(st.st_mode)) return {p, false};
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {p, true};
    if (S_ISDIR(st.st_mode)) throw Error(fmt::format("{}: is a folder, not a file", target.string()));
    if (S_ISBLK(st.st_mode))
      throw Error(fmt::format("{}: is a block device (a disk); Penumbra does not write files onto one", target.string()));
    throw Error(fmt::format("{}: is a socket or another special file, not a file to write", target.string()));
  }
}

void createFolder(const std::filesystem::path& folder, const std::filesystem::path& target) {
  if (folder.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw Error(fmt::format("{}: cannot create the folder {} ({})", target.string(), folder.string(), ec.message()));
}

/// Opens a device or FIFO for writing. A FIFO is opened without blocking first: with nobody
/// reading it the open fails (ENXIO) instead of waiting forever.
int openWriteThrough(const std::filesystem::path& path, const std::filesystem::path& target) {
  const int fd = open(path.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENXIO) throw Error(fmt::format("{}: is a FIFO that no process reads", target.string()));
    throw Error(fmt::format("{}: cannot open it for writing ({})", target.string(), errnoText()));
  }
  const int flags = fcntl(fd, F_GETFL);
  if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0) {
    const std::string why = errnoText();
    close(fd);
    throw Error(fmt::format("{}: cannot open it for writing ({})", target.string(), why));
  }
  return fd;
}

void writeAll(int fd, const char* data, size_t size, const std::filesystem::path& target) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(fmt::format("{}: cannot write ({})", target.string(), n < 0 ? errnoText() : "nothing written"));
    data += n;
    size -= static_cast<size_t>(n);
  }
}

/// Creates and removes a file in `folder`: the one sure test that files can be made there. The
/// folders it had to create go again, so that a check leaves nothing behind (a run that fails on
/// a later check writes nothing); the writers create them when they write.
void probeFolder(const std::filesystem::path& folder, const std::filesystem::path& target) {
  const std::filesystem::path dir = folder.empty() ? std::filesystem::path(".") : folder;
  std::vector<std::filesystem::path> created;  // deepest first
  std::error_code ec;
  for (std::filesystem::path p = std::filesystem::absolute(dir, ec); !ec && !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    created.push_back(p);
    if (p == p.parent_path()) break;
  }
  createFolder(dir, target);
  const std::filesystem::path probe = dir / fmt::format(".penumbra-probe.{}.{}", getpid(), gTemporaryCounter.fetch_add(1));
  const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  const int openErrno = errno;
  if (fd >= 0) {
    close(fd);
    unlink(probe.c_str());
  }
  for (const std::filesystem::path& p : created) std::filesystem::remove(p, ec);  // only if still empty
  errno = openErrno;
  if (fd < 0) throw Error(fmt::format("{}: cannot create files in {} ({})", target.string(), dir.string(), errnoText()));
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : mTarget(std::move(target)) {
  const Destination d = resolve(mTarget);
  mDestination = d.path;
  const std::string unique = fmt::format(".tmp.{}.{}", getpid(), gTemporaryCounter.fetch_add(1));
  if (d.writeThrough) {
    // A device's folder (/dev) is no place for a temporary file.
    mTemporary = std::filesystem::temp_directory_path() / ("penumbra" + unique);
    mWriteThroughFd = openWriteThrough(mDestination, mTarget);
  } else {
    createFolder(mDestination.parent_path(), mTarget);
    // Unique per process and call: two runs (or threads) writing the same file never share one.
    // Within the name limit: the target's name is cut short where it leaves no room.
    const std::string name = mDestination.filename().string();
    const size_t max = maxNameBytes(mDestination.parent_path());
    mTemporary = mDestination.parent_path() / (name.substr(0, std::min(name.size(), max - std::min(max, unique.size()))) + unique);
  }
}

AtomicFile::~AtomicFile() {
  if (mWriteThroughFd >= 0) close(mWriteThroughFd);
  std::error_code ignored;
  if (!mCommitted) std::filesystem::remove(mTemporary, ignored);
}

void AtomicFile::commit() {
  if (mWriteThroughFd < 0) {
    std::error_code ec;
    std::filesystem::rename(mTemporary, mDestination, ec);
    if (ec) throw Error(fmt::format("{}: cannot replace it ({})", mTarget.string(), ec.message()));
    mCommitted = true;
    return;
  }
  std::ifstream in(mTemporary, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: cannot read back the temporary file {}", mTarget.string(), mTemporary.string()));
  std::vector<char> block(kCopyBlockBytes);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    writeAll(mWriteThroughFd, block.data(), static_cast<size_t>(in.gcount()), mTarget);
  }
  if (!in.eof()) throw Error(fmt::format("{}: cannot read back the temporary file {}", mTarget.string(), mTemporary.string()));
  const int fd = mWriteThroughFd;
  mWriteThroughFd = -1;
  if (close(fd) != 0) throw Error(fmt::format("{}: cannot write ({})", mTarget.string(), errnoText()));
  mCommitted = true;
  std::error_code ignored;
  std::filesystem::remove(mTemporary, ignored);
}

void checkOutputFile(const std::filesystem::path& path) {
  const Destination d = resolve(path);
  if (d.writeThrough) {
    if (access(d.path.c_str(), W_OK) != 0) throw Error(fmt::format("{}: not writable ({})", path.string(), errnoText()));
    return;
  }
  probeFolder(d.path.parent_path(), path);
}

void checkOutputFolder(const std::filesystem::path& path) {
  if (path.empty()) throw Error("an empty path names no folder");
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);  // follows links
  if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
    throw Error(fmt::format("{}: exists and is not a folder", path.string()));
  probeFolder(path, path);
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
  writeBinaryFile(path, {std::span<const char>(text.data(), text.size())});
}

void writeBinaryFile(const std::filesystem::path& path, std::initializer_list<std::span<const char>> blocks) {
  writeBinaryFile(path, std::span<const std::span<const char>>(blocks.begin(), blocks.size()));
}

void writeBinaryFile(const std::filesystem::path& path, std::span<const std::span<const char>> blocks) {
  AtomicFile file(path);
  {
    errno = 0;
    std::ofstream out(file.temporary(), std::ios::binary | std::ios::trunc);
    if (!out)
      throw Error(fmt::format("{}: cannot create its temporary file in {} ({})", path.string(),
                              file.temporary().parent_path().string(), errno != 0 ? errnoText() : "open failed"));
    for (std::span<const char> b : blocks) out.write(b.data(), static_cast<std::streamsize>(b.size()));
    out.close();
    if (!out) throw Error(fmt::format("{}: cannot write ({})", path.string(), errno != 0 ? errnoText() : "write failed"));
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
