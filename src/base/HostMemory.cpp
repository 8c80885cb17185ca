#include "base/HostMemory.h"

#include <algorithm>
#include <fstream>
#include <optional>
#include <string>

#include <sys/resource.h>

namespace penumbra {
namespace {

constexpr uint64_t kKiB = 1024;

/// A "Key:   123 kB" line of a /proc file, in bytes.
std::optional<uint64_t> procKib(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) return std::stoull(line.substr(key.size() + 1)) * kKiB;
  return std::nullopt;
}

std::optional<uint64_t> readNumber(const char* file) {
  std::ifstream in(file);
  uint64_t v = 0;
  if (in >> v) return v;
  return std::nullopt;  // absent, or "max"
}

}  // namespace

uint64_t availableHostBytes() {
  uint64_t available = procKib("/proc/meminfo", "MemAvailable").value_or(UINT64_MAX);
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const uint64_t used = procKib("/proc/self/status", "VmSize").value_or(0);
    available = std::min<uint64_t>(available, limit.rlim_cur > used ? limit.rlim_cur - used : 0);
  }
  const std::optional<uint64_t> max = readNumber("/sys/fs/cgroup/memory.max"), current = readNumber("/sys/fs/cgroup/memory.current");
  if (max && current) available = std::min(available, *max > *current ? *max - *current : 0);
  return available;
}

uint64_t totalHostBytes() { return procKib("/proc/meminfo", "MemTotal").value_or(0); }

}  // namespace penumbra
