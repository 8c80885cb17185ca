// The search of `penumbra tune` without GL: candidates inside the table's ranges, neighbours,
// the successive-halving cut, the Pareto front and the budget pick.
#include "tuner/TuneSearch.h"

#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

using namespace penumbra;
using namespace penumbra::report;

namespace {

std::vector<TuneDim> pcfSpace(int mapSize = 2048) {
  const Parameterized f(filterParams("pcf"));
  std::vector<float> current;
  for (const ParamDesc& d : f.paramDescs()) current.push_back(f.param(d.key));
  return tuneSpace(f.paramDescs(), current, {.size = mapSize, .texels = int64_t{mapSize} * mapSize});
}

// csm's own parameters (no filter), `cascades` maps of 2048² by default.
std::vector<TuneDim> csmSpace(std::span<const std::string> fixed = {}) {
  const Parameterized p(projectionParams("csm"));
  std::vector<float> current;
  for (const ParamDesc& d : p.paramDescs()) current.push_back(p.param(d.key));
  constexpr int kSide = 2048;
  return tuneSpace(p.paramDescs(), current, {.size = kSide, .texels = int64_t{4} * kSide * kSide}, fixed);
}

TunePoint point(double costMs, double error, double memoryMiB) {
  return {.error = error, .costMs = costMs, .memoryMiB = memoryMiB};
}

bool isPowerOfTwo(float v) { return v > 0.0f && std::exp2(std::round(std::log2(v))) == v; }

}  // namespace

TEST(TuneSearch, SpaceTakesItsRangesFromTheParameterTable) {
  const std::vector<TuneDim> space = pcfSpace();
  ASSERT_FALSE(space.empty());
  for (const TuneDim& d : space) {
    EXPECT_LE(d.desc.min, d.lo) << d.desc.key;
    EXPECT_LE(d.hi, d.desc.max) << d.desc.key;
    EXPECT_LE(d.lo, d.def) << d.desc.key;
    EXPECT_LE(d.def, d.hi) << d.desc.key;
  }
  const auto find = [&](std::string_view key) {
    return std::find_if(space.begin(), space.end(), [&](const TuneDim& d) { return d.desc.key == key; });
  };
  ASSERT_NE(find("pcf.kernel"), space.end());
  EXPECT_EQ(find("pcf.kernel")->scale, TuneScale::Choice);
  ASSERT_NE(find("pcf.radiusTexels"), space.end());
  EXPECT_EQ(find("pcf.radiusTexels")->scale, TuneScale::Log);  // 0..32 around 2: factors matter
  ASSERT_NE(find(kMapSizeKey), space.end());
  EXPECT_EQ(find(kMapSizeKey)->lo, 1024.0f);
  EXPECT_EQ(find(kMapSizeKey)->hi, 4096.0f);
}

TEST(TuneSearch, FixedKeysAndZeroMapSizeAreLeftOut) {
  const Parameterized f(filterParams("pcf"));
  std::vector<float> current;
  for (const ParamDesc& d : f.paramDescs()) current.push_back(f.param(d.key));
  const std::vector<std::string> fixed = {"pcf.kernel"};
  const std::vector<TuneDim> space = tuneSpace(f.paramDescs(), current, TuneMapDefault{}, fixed);
  for (const TuneDim& d : space) {
    EXPECT_NE(d.desc.key, "pcf.kernel");
    EXPECT_NE(d.desc.key, kMapSizeKey);
  }
}

TEST(TuneSearch, LatinHypercubeStaysInRangeSnapsAndCoversEachRange) {
  const std::vector<TuneDim> space = pcfSpace();
  constexpr int kCount = 32;
  const std::vector<TuneCandidate> cands = latinHypercube(space, kCount, 7);
  ASSERT_GT(cands.size(), kCount / 2u);
  for (const TuneCandidate& c : cands) {
    ASSERT_EQ(c.size(), space.size());
    for (size_t d = 0; d < space.size(); ++d) {
      EXPECT_GE(c[d], space[d].lo * (1.0f - 1e-3f)) << space[d].desc.key;
      EXPECT_LE(c[d], space[d].hi * (1.0f + 1e-3f)) << space[d].desc.key;
      EXPECT_GE(c[d], space[d].desc.min);
      EXPECT_LE(c[d], space[d].desc.max);
      if (space[d].desc.isInteger()) {
        EXPECT_EQ(c[d], std::round(c[d])) << space[d].desc.key;
      }
      if (space[d].powerOfTwo) {
        EXPECT_TRUE(isPowerOfTwo(c[d])) << c[d];
      }
    }
  }
  // Stratified: every choice and both halves of every continuous range are sampled.
  for (size_t d = 0; d < space.size(); ++d) {
    float lo = space[d].hi, hi = space[d].lo;
    for (const TuneCandidate& c : cands) {
      lo = std::min(lo, c[d]);
      hi = std::max(hi, c[d]);
    }
    if (space[d].scale == TuneScale::Choice) {
      EXPECT_EQ(lo, space[d].lo) << space[d].desc.key;
      EXPECT_EQ(hi, space[d].hi) << space[d].desc.key;
    } else {
      const float mid = space[d].scale == TuneScale::Log ? std::sqrt(space[d].lo * space[d].hi)
                                                         : 0.5f * (space[d].lo + space[d].hi);
      EXPECT_LT(lo, mid) << space[d].desc.key;
      EXPECT_GT(hi, mid) << space[d].desc.key;
    }
  }
  EXPECT_EQ(cands, latinHypercube(space, kCount, 7));  // deterministic for a seed
}

TEST(TuneSearch, NeighboursChangeOneDimensionWithinRange) {
  const std::vector<TuneDim> space = pcfSpace();
  const TuneCandidate center = defaultCandidate(space);
  const std::vector<TuneCandidate> next = neighbours(space, center);
  ASSERT_GE(next.size(), space.size());
  for (const TuneCandidate& c : next) {
    int changed = 0;
    for (size_t d = 0; d < space.size(); ++d) {
      if (c[d] != center[d]) ++changed;
      EXPECT_GE(c[d], space[d].desc.min);
      EXPECT_LE(c[d], space[d].desc.max);
    }
    EXPECT_EQ(changed, 1);
  }
}

TEST(TuneSearch, ParamsListOnlyWhatDiffersFromTheDefault) {
  const std::vector<TuneDim> space = pcfSpace(1024);
  TuneCandidate c = defaultCandidate(space);
  EXPECT_TRUE(tuneParams(space, c).empty());
  EXPECT_EQ(tuneMaps(space, c, {.size = 1024, .texels = 1024 * 1024}), (TuneMaps{.size = 1024, .budgetTexels = 0}));
  for (size_t d = 0; d < space.size(); ++d) {
    if (space[d].desc.key == "pcf.radiusTexels") c[d] = 3.5f;
    if (space[d].desc.key == "pcf.kernel") c[d] = 0.0f;
    if (space[d].desc.key == kMapSizeKey) c[d] = 2048.0f;
  }
  const auto params = tuneParams(space, c);
  ASSERT_EQ(params.size(), 2u);
  EXPECT_EQ(params[0], (std::pair<std::string, std::string>{"pcf.kernel", "box"}));
  EXPECT_EQ(params[1], (std::pair<std::string, std::string>{"pcf.radiusTexels", "3.5"}));
  EXPECT_EQ(tuneMaps(space, c, {.size = 1024, .texels = 1024 * 1024}), (TuneMaps{.size = 2048, .budgetTexels = 0}));
}

TEST(TuneSearch, AMapCountMakesTheMapBudgetTheDimensionSoCountStepsKeepTheMemory) {
  const std::vector<TuneDim> space = csmSpace();
  const auto dim = [&](std::string_view key) {
    const auto it = std::find_if(space.begin(), space.end(), [&](const TuneDim& d) { return d.desc.key == key; });
    return it == space.end() ? std::optional<size_t>() : std::optional<size_t>(static_cast<size_t>(it - space.begin()));
  };
  ASSERT_TRUE(dim(kMapBudgetKey));
  EXPECT_FALSE(dim(kMapSizeKey));
  const size_t budget = *dim(kMapBudgetKey), count = *dim("csm.cascades");
  constexpr float kDefaultTexels = 4.0f * 2048.0f * 2048.0f;
  EXPECT_EQ(space[budget].def, kDefaultTexels);
  EXPECT_EQ(space[budget].lo, kDefaultTexels / 4.0f);  // the memory a map size from half to twice spans
  EXPECT_EQ(space[budget].hi, kDefaultTexels * 4.0f);

  // The default renders as compare's default (no budget); any other count at the same budget
  // asks for the budget, one map's side being the whole of it.
  const TuneMapDefault maps{.size = 2048, .texels = 4 * 2048 * 2048};
  const TuneCandidate def = defaultCandidate(space);
  EXPECT_EQ(tuneMaps(space, def, maps), (TuneMaps{.size = 2048, .budgetTexels = 0}));
  TuneCandidate two = def;
  two[count] = 2.0f;
  EXPECT_EQ(tuneMaps(space, two, maps), (TuneMaps{.size = 4096, .budgetTexels = maps.texels}));
  TuneCandidate more = def;
  more[budget] = 2.0f * kDefaultTexels;
  EXPECT_EQ(tuneMaps(space, more, maps), (TuneMaps{.size = 5792, .budgetTexels = 2 * maps.texels}));
  EXPECT_TRUE(tuneParams(space, more).empty());  // not a --set key
  // Coordinate descent's count steps keep the budget: equal memory.
  for (const TuneCandidate& n : neighbours(space, def))
    if (n[count] != def[count]) {
      EXPECT_EQ(n[budget], def[budget]);
    }
  // Candidates sit on the default's octaves of texels.
  for (const TuneCandidate& c : latinHypercube(space, 16, 3)) {
    const float octaves = std::log2(c[budget] / kDefaultTexels);
    EXPECT_EQ(octaves, std::round(octaves)) << c[budget];
  }
  // Fixed, the budget stays the default's: equal memory for every candidate.
  const std::vector<std::string> fixed = {std::string(kMapBudgetKey)};
  const std::vector<TuneDim> equal = csmSpace(fixed);
  EXPECT_TRUE(std::none_of(equal.begin(), equal.end(), [](const TuneDim& d) { return d.desc.key == kMapBudgetKey; }));
  TuneCandidate three = defaultCandidate(equal);
  for (size_t d = 0; d < equal.size(); ++d)
    if (equal[d].desc.key == "csm.cascades") three[d] = 3.0f;
  EXPECT_EQ(tuneMaps(equal, three, maps), (TuneMaps{.size = 4096, .budgetTexels = maps.texels}));
  EXPECT_EQ(tuneMaps(equal, defaultCandidate(equal), maps), (TuneMaps{.size = 2048, .budgetTexels = 0}));
}

TEST(TuneSearch, TheCombinedMoveTakesEveryImprovedDimensionAtItsBestStep) {
  const TuneCandidate center = {1.0f, 2.0f, 3.0f};
  // Best first: dimension 1 down, dimension 1 up (worse: ignored), dimension 2 up.
  const std::vector<TuneCandidate> better = {{1.0f, 1.5f, 3.0f}, {1.0f, 2.5f, 3.0f}, {1.0f, 2.0f, 4.0f}};
  EXPECT_EQ(combinedMove(center, better), (TuneCandidate{1.0f, 1.5f, 4.0f}));
  // One dimension only: no combined move (the best neighbour is the move).
  EXPECT_FALSE(combinedMove(center, std::vector<TuneCandidate>{{1.0f, 1.5f, 3.0f}, {1.0f, 2.5f, 3.0f}}));
  EXPECT_FALSE(combinedMove(center, {}));
}

TEST(TuneSearch, FrontAndBudgetPick) {
  const std::vector<TunePoint> pts = {
      point(0.10, 1.0, 4.0),   // 0: on the front
      point(0.05, 2.0, 4.0),   // 1: on the front (the cheapest)
      point(0.20, 0.5, 4.0),   // 2: on the front
      point(0.30, 0.6, 4.0),   // 3: dominated by 2
      point(0.40, 0.2, 64.0),  // 4: on the front, but large
  };
  EXPECT_EQ(tuneFront(pts), (std::vector<size_t>{1, 0, 2, 4}));
  EXPECT_EQ(tuneFront(pts, 16.0), (std::vector<size_t>{1, 0, 2}));
  EXPECT_EQ(pickRecommended(pts, {}), 4u);
  const auto budget = [](std::optional<double> ms, std::optional<double> mib, std::optional<double> maxError) {
    return TuneBudget{.costMs = ms, .memoryMiB = mib, .maxError = maxError};
  };
  EXPECT_EQ(pickRecommended(pts, budget(0.25, {}, {})), 2u);
  EXPECT_EQ(pickRecommended(pts, budget(1.0, 16.0, {})), 2u);
  EXPECT_EQ(pickRecommended(pts, budget({}, {}, 1.0)), 0u);  // the cheapest within the error target
  EXPECT_EQ(pickRecommended(pts, budget(0.01, {}, {})), std::nullopt);
}

TEST(TuneSearch, HalvingKeepsTheFrontThenTheMostAccurate) {
  const std::vector<TunePoint> pts = {
      point(1.0, 0.9, 1), point(0.1, 0.95, 1), point(2.0, 0.3, 1),
      point(3.0, 0.35, 1), point(4.0, 0.4, 1), point(5.0, 0.8, 1),
  };
  // front: 1 (0.1, 0.95), 0 (1.0, 0.9), 2 (2.0, 0.3); by error 2, 0, 1; then 3.
  EXPECT_EQ(halvingSurvivors(pts, 4), (std::vector<size_t>{2, 0, 1, 3}));
  EXPECT_EQ(halvingSurvivors(pts, 2), (std::vector<size_t>{2, 0}));
  EXPECT_EQ(halvingSurvivors(pts, 10).size(), pts.size());
}
