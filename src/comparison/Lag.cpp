// Lag and ghosting (Lag.h).
#include "comparison/Lag.h"

#include <algorithm>
#include <vector>

namespace penumbra {

LagCounts countLag(const FlickerFrame& now, std::span<const FlickerFrame* const> earlier, const LagOptions& o) {
  const size_t n = now.v.size();
  std::vector<uint8_t> changing(n, 0);
  const size_t depth = std::min(earlier.size(), static_cast<size_t>(std::max(o.frames, 0)));
  for (size_t k = 0; k < depth; ++k) {
    const FlickerFrame& before = *earlier[k];
    // Each pixel of `now` followed back to the point it saw in `before`.
    for (const FollowedPoint& p : followPoints(now, before))
      if (std::abs(now.vRef[p.from] - before.vRef[p.to]) > o.changeV) changing[p.from] = 1;
  }
  LagCounts c;
  for (size_t i = 0; i < n; ++i) {
    if (!changing[i]) continue;
    const double e = static_cast<double>(now.v[i]) - static_cast<double>(now.vRef[i]);
    ++c.pixels;
    c.sumSquaredError += e * e;
    if (e < -o.ghostV) ++c.tooDark;
    if (e > o.ghostV) ++c.tooBright;
  }
  return c;
}

}  // namespace penumbra
