#pragma once
// Runs the penumbra binary and captures exit code, stdout and stderr.
#include <string>

namespace penumbra::test {

struct RunResult {
  int exitCode = -1;
  std::string out, err;
};

/// Runs `penumbra <args>` in `workDir` (created if needed). `args` is passed to the shell as is.
/// `launcher` goes before the binary (e.g. "xvfb-run -a" for the viewer). `stdoutTo`, when
/// given, receives stdout instead of RunResult::out (e.g. "/dev/full").
RunResult runPenumbra(const std::string& args, const std::string& workDir = "", const std::string& launcher = "",
                      const std::string& stdoutTo = "");

/// A fresh empty folder under the system temp dir.
std::string freshDir(const std::string& name);

}  // namespace penumbra::test
