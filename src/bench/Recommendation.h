#pragma once
// "Which technique should I use?", answered from a bench run's own rows (never by hand): for each
// situation users bring, a built-in scene that stands for it and the error that matters there;
// among the configurations measured on that scene, three picks by the rule below. The report's
// first section and docs/choosing.md show them (ChoosingPage.h); results.json carries them.
//
// The rule, per situation:
//  - candidates: the rows of the situation's scene at its own light (BenchResults: sceneRows),
//    except, where casters may move, techniques with one-off work (a baked field is only valid
//    while nothing moves: sdf);
//  - each is scored in motion as well as still (BenchConfig::motion): its error is the mean over
//    the still frame and the frames of the scene's animation or a camera walk; its flicker is
//    the share of surface points whose V changes between consecutive frames while V_ref holds;
//  - acceptable: flicker ≤ kMaxFlickerPct and error ≤ kAcceptableErrorFactor × the lowest error
//    among the candidates that do not flicker beyond it;
//  - contenders: the acceptable candidates that no other acceptable one beats clearly (cheaper
//    beyond both spreads and more accurate); they are timed again in interleaved rounds
//    (RoundCosts), and the picks and their costs come from those rounds;
//  - cheapest acceptable: the contender with the lowest whole cost; contenders whose cost ratio
//    to it spans 1 over the rounds (p10–p90) tie with it, and the simplest of them (the least
//    GPU memory) is picked;
//  - best: the lowest error; contenders whose error ratio to it spans 1 over the frames tie
//    with it, and the cheapest of them is picked;
//  - balanced: the lowest whole cost × error (the knee of the front on log-log axes).
// A tie is named on the page. Each pick is an acceptable configuration that nothing acceptable
// beats clearly in both cost and error.
#include "bench/BenchResults.h"

#include <optional>
#include <string>
#include <vector>

namespace penumbra::report {

enum class ErrorMetric {
  Rmse,          ///< RMSE of V over every pixel that faces the light
  PenumbraRmse,  ///< RMSE of V over the reference's penumbra pixels only
  /// RMSE of V over RGB against the RGB reference (translucent casters: a technique whose V is
  /// one channel counts as grey, so a shadow of the right darkness and the wrong hue is an
  /// error). Where a row has no colour metric (no translucent caster: V_ref is grey) it reads
  /// the RMSE, which is then the same number.
  ColourRmse,
};

/// A situation users bring, the scene that stands for it and the error that decides.
struct Situation {
  const char* id;     ///< anchor and JSON key: "contact-hardening"
  const char* title;  ///< "Contact-hardening shadow of a small light"
  const char* scene;  ///< the built-in scene measured for it
  ErrorMetric metric;
  bool staticCasters;  ///< casters never move: one-off work (a bake) is allowed
  const char* why;     ///< what the scene shows and why that metric
};

inline constexpr Situation kSituations[] = {
    {"contact-hardening", "Contact-hardening shadow of a small light", "pen", ErrorMetric::PenumbraRmse, false,
     "a pencil leaning on the floor under a spherical spot light of 0.12 m radius: sharp where the pencil touches "
     "the floor, wider along its length. The error is taken over the reference's penumbra pixels, where that "
     "widening is."},
    {"wide-sun", "Wide sun over a large view", "city", ErrorMetric::Rmse, false,
     "a 640 m street under a low sun, seen from eye height: the shadow must hold near the camera and hundreds of "
     "metres away (perspective aliasing). The error is taken over every pixel that faces the sun."},
    {"thin-casters", "Thin overlapping casters", "fence", ErrorMetric::Rmse, false,
     "rows of thin slats before a wall: occluders overlap in depth, where variance-based filters bleed light and "
     "thin shadows alias. The error is taken over every pixel that faces the light."},
    {"static", "Static scene: nothing moves", "boxes", ErrorMetric::Rmse, true,
     "boxes and spheres on a plane under the sun, casters that never move: work done once (sdf's distance-field "
     "bake) is allowed, shown beside the per-frame cost. The error is taken over every pixel that faces the sun."},
    {"translucent", "Light through translucent casters", "glass", ErrorMetric::ColourRmse, false,
     "a stained-glass canopy of four coloured panes and a tinted pane over a floor under the sun: the light keeps "
     "each pane's colour, and the product of two where it crosses both. A technique that ignores translucency "
     "shadows the panes as opaque; one whose V is one channel gets the darkness without the hue. The error is the "
     "RMSE over red, green and blue against the RGB reference (a one-channel V counts as grey), over every pixel "
     "that faces the sun."},
};

/// Acceptable: an error at most this many times the lowest error any candidate reached in the
/// situation. On the built-in scenes the techniques' errors span 10× and more; within 2× of the
/// best keeps the family that gets the situation's shadow right and drops the ones whose error
/// shows (hard edges under a soft light, light bleeding, a map stretched over 600 m).
inline constexpr double kAcceptableErrorFactor = 2.0;

/// Acceptable: at most this share (%) of the followed surface points flicker between consecutive
/// frames of the motion (comparison/Flicker.h: V changes by more than 0.1 while V_ref changes by
/// less than 0.02) — one point in a thousand, the bar `tune` holds acne to. On city's walk one
/// uniform map flickers 3 %, tsm 0.5 %, psm 0.2 %, stabilised cascades 0.06 % (pcf, 640×360).
inline constexpr double kMaxFlickerPct = 0.1;

/// At most this many contenders per situation are timed again in interleaved rounds (the
/// cheapest first, and always the most accurate): each costs a renderer held for the rounds.
inline constexpr size_t kMaxContenders = 8;

enum class Budget { CheapestAcceptable, Balanced, Best };
inline constexpr Budget kBudgets[] = {Budget::CheapestAcceptable, Budget::Balanced, Budget::Best};
const char* budgetName(Budget b);  ///< "cheapest acceptable", "balanced", "best"
const char* budgetKey(Budget b);   ///< "cheapest_acceptable", "balanced", "best" (JSON)

/// What `metric` reads on a row's still frame.
double situationError(ErrorMetric metric, const BenchRow& row);
/// What `metric` reads on each frame the row was scored on: the still frame, then its motion's.
std::vector<double> frameErrors(ErrorMetric metric, const BenchRow& row);
/// The error that decides: the mean of frameErrors.
double motionError(ErrorMetric metric, const BenchRow& row);
/// The row's flicker (%) over its motion; 0 for a row scored still only.
double flickerPct(const BenchRow& row);
/// The whole cost the picks compare: the interleaved rounds' when the row has them, else its own
/// timed frames'.
const TimeStats& pickCost(const BenchRow& row);

/// Whether two rows' costs are indistinguishable: the per-round ratio of their interleaved
/// costs spans 1 from p10 to p90; rows without rounds: their p10–p90 ranges overlap.
bool costsTie(const BenchRow& a, const BenchRow& b);
/// The per-round cost ratio a/b (median, p10–p90); empty without common rounds.
std::optional<TimeStats> costRatio(const BenchRow& a, const BenchRow& b);
/// Whether two rows' errors are indistinguishable: the per-frame ratio of their errors spans 1
/// from p10 to p90 (one frame each: only equal errors tie).
bool errorsTie(ErrorMetric metric, const BenchRow& a, const BenchRow& b);
/// The per-frame error ratio a/b (median, p10–p90); empty when the frames differ in number.
std::optional<TimeStats> errorRatio(ErrorMetric metric, const BenchRow& a, const BenchRow& b);

/// Marks the configurations the situations judge (a situation's scene at its own light) to be
/// scored in motion too (BenchConfig::motion).
void markMotion(std::vector<BenchConfig>& configs);
const char* metricName(ErrorMetric metric);  ///< "RMSE", "penumbra RMSE", "colour RMSE"
const char* metricKey(ErrorMetric metric);   ///< "rmse", "penumbra_rmse", "rmse_rgb" (the results column)

/// A pick that tied: the rows it tied with (by cost for the cheapest, by error for the best) and
/// the row the plain order would have picked among them.
struct PickTie {
  std::vector<size_t> with;   ///< the other rows of the tie (indices into results.rows)
  size_t first = 0;           ///< the row first in the plain order (lowest cost or lowest error)
};

struct SituationPicks {
  const Situation* situation = nullptr;
  std::vector<size_t> candidates;     ///< indices into results.rows
  std::vector<std::string> excluded;  ///< "sdf · uniform: one-off work (...)", one per row left out
  /// Candidates that flicker beyond kMaxFlickerPct: not acceptable whatever their error.
  std::vector<size_t> flickering;
  std::vector<size_t> acceptable;     ///< acceptable candidates
  std::vector<size_t> front;          ///< whole-cost Pareto front of the candidates, ascending cost
  std::vector<size_t> contenders;     ///< what the interleaved rounds time (the picks among them)
  double bestError = 0.0, acceptableError = 0.0;
  bool motion = false;                ///< the candidates were scored in motion
  bool retimed = false;               ///< the picks' costs come from interleaved rounds
  std::optional<size_t> cheapestAcceptable, balanced, best;  ///< rows; empty when nothing is acceptable
  std::optional<PickTie> cheapestTie, bestTie;
  std::optional<size_t> pick(Budget b) const;
  /// The budgets that picked `row`, in kBudgets order.
  std::vector<Budget> budgetsOf(size_t row) const;
};

/// One entry per kSituations entry, in that order; a situation whose scene the run did not
/// measure has no candidates (and no picks).
std::vector<SituationPicks> recommend(const BenchResults& results);

}  // namespace penumbra::report
