#pragma once
// The one place files are written: to a temporary name beside the target (unique per process
// and call), then renamed over it, so a failed or concurrent run never leaves half a file.
#include <filesystem>

namespace penumbra {

class AtomicFile {
public:
  /// Creates the target's folder if needed (throws penumbra::Error naming it if it cannot).
  explicit AtomicFile(std::filesystem::path target);
  /// Removes the temporary file unless commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Where to write the contents.
  const std::filesystem::path& temporary() const { return mTemporary; }
  const std::filesystem::path& target() const { return mTarget; }
  /// Renames the temporary file over the target. Throws penumbra::Error naming the target.
  void commit();

private:
  std::filesystem::path mTarget, mTemporary;
  bool mCommitted = false;
};

}  // namespace penumbra
