#include "CliSupport.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace penumbra::test {

std::string freshDir(const std::string& name) {
  // The process id keeps concurrent test runs (several build trees) apart.
  const auto dir = std::filesystem::temp_directory_path() / ("penumbra-cli-" + name + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

RunResult runPenumbra(const std::string& args, const std::string& workDir, const std::string& launcher,
                      const std::string& stdoutTo) {
  // Each run gets its own folder: CTest runs tests in parallel processes.
  static int counter = 0;
  const std::string dir = workDir.empty() ? freshDir("run-" + std::to_string(counter++)) : workDir;
  const std::string outFile = stdoutTo.empty() ? dir + "/.stdout" : stdoutTo, errFile = dir + "/.stderr";
  const std::string cmd = "cd '" + dir + "' && " + launcher + " '" PENUMBRA_BINARY "' " + args + " > '" + outFile + "' 2> '" + errFile + "' < /dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto slurp = [](const std::string& f) {
    std::ifstream in(f);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  if (stdoutTo.empty()) r.out = slurp(outFile);
  r.err = slurp(errFile);
  return r;
}

}  // namespace penumbra::test
