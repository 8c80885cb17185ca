#pragma once
// How much host memory (RAM) there is: what a scene's memory estimate and the image-size check
// are held against.
#include <cstdint>

namespace penumbra {

/// Host memory this process may still take: what the kernel calls available (MemAvailable),
/// bounded by an address-space limit (ulimit -v) and a cgroup v2 memory limit when there are ones.
uint64_t availableHostBytes();

/// The machine's RAM (MemTotal); 0 when /proc does not say.
uint64_t totalHostBytes();

}  // namespace penumbra
