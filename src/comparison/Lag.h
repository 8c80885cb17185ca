#pragma once
// Lag (ghosting): the error of a technique on the pixels whose reference changed lately, where a
// technique that reuses earlier frames (temporal accumulation) shows what it still remembers.
// A pixel of frame f is "changing" when the surface point it sees, followed on its object into
// any of the frames f−1 … f−LagOptions::frames (comparison/Flicker.h's followPoints, backwards),
// had a V_ref that differs from its V_ref now by more than LagOptions::changeV. Over the
// changing pixels of every frame: lag_rmse = sqrt(mean (V − V_ref)²), and ghost_pct = the share
// with |V − V_ref| > LagOptions::ghostV (split into too dark and too bright). A technique that
// keeps nothing from earlier frames still has its ordinary error there; compare it with the
// same filter without accumulation. No GL here: the frames are read-backs.
#include "comparison/Flicker.h"

#include <cmath>
#include <cstddef>
#include <span>

namespace penumbra {

struct LagOptions {
  int frames = 4;          ///< how many earlier frames a change is looked for in
  float changeV = 0.1f;    ///< V_ref changed by more than this: the pixel is changing
  float ghostV = 0.1f;     ///< |V − V_ref| beyond this on a changing pixel: a ghost
};

struct LagCounts {
  size_t pixels = 0;              ///< changing pixels, over the frames
  double sumSquaredError = 0.0;   ///< Σ (V − V_ref)² over them
  size_t tooDark = 0, tooBright = 0;  ///< V < V_ref − ghostV, V > V_ref + ghostV
  LagCounts& operator+=(const LagCounts& o) {
    pixels += o.pixels;
    sumSquaredError += o.sumSquaredError;
    tooDark += o.tooDark;
    tooBright += o.tooBright;
    return *this;
  }
  /// lag_rmse (0 when no pixel changed).
  double rmse() const { return pixels ? std::sqrt(sumSquaredError / static_cast<double>(pixels)) : 0.0; }
  /// ghost_pct: 100 · (too dark + too bright) / changing pixels.
  double ghostPct() const { return pctOf(tooDark + tooBright); }
  /// ghost_dark_pct: the too-dark share alone (a shadow that stays where it left).
  double darkPct() const { return pctOf(tooDark); }
  double pctOf(size_t count) const { return pixels ? 100.0 * static_cast<double>(count) / static_cast<double>(pixels) : 0.0; }
};

/// The changing pixels of `now` and the technique's error there. `earlier` are the frames before
/// it, nearest first (only the first LagOptions::frames are read); `now.v` is the technique's V.
LagCounts countLag(const FlickerFrame& now, std::span<const FlickerFrame* const> earlier, const LagOptions& options = {});

}  // namespace penumbra
