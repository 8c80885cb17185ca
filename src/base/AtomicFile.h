#pragma once
// The one place files are written. What the target path names decides how:
//  - a new name or a regular file: a temporary file beside it (unique per process and call),
//    renamed over it, so a failed or concurrent run never leaves half a file;
//  - a symbolic link: followed (the link stays a link; the file it names is written as above);
//  - a character device or a FIFO (/dev/null, a pipe someone reads): written through: the
//    contents go to a temporary file in the system's temporary folder first, then are copied
//    into the target, which is never created, truncated away or replaced;
//  - a folder, a block device (a disk), a socket: refused with an Error naming the path.
#include <filesystem>

namespace penumbra {

class AtomicFile {
public:
  /// Classifies the target and creates its folder if needed; throws penumbra::Error naming it
  /// if it cannot receive a file (see above; a FIFO nobody reads is an error, not a hang).
  explicit AtomicFile(std::filesystem::path target);
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Where to write the contents.
  const std::filesystem::path& temporary() const { return mTemporary; }
  const std::filesystem::path& target() const { return mTarget; }
  /// Renames the temporary file over the target (or copies it into a device or FIFO). Throws
  /// penumbra::Error naming the target.
  void commit();

private:
  std::filesystem::path mTarget;       // as the caller named it (for messages)
  std::filesystem::path mDestination;  // after following symbolic links
  std::filesystem::path mTemporary;
  int mWriteThroughFd = -1;            // open device or FIFO; -1 when renaming
  bool mCommitted = false;
};

}  // namespace penumbra
