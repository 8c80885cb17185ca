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
//  - acceptable: error ≤ kAcceptableErrorFactor × the lowest error among the candidates;
//  - cheapest acceptable: the acceptable candidate with the lowest whole cost (ties: lower error);
//  - best: the lowest error (ties: lower cost);
//  - balanced: the acceptable candidate with the lowest whole cost × error (ties: lower cost),
//    the knee of the front on log-log axes.
// Each pick is on the whole-cost Pareto front of the candidates: a configuration that is both
// cheaper and more accurate would be acceptable too and win every one of the three orders.
#include "report/BenchResults.h"

#include <optional>
#include <string>
#include <vector>

namespace penumbra::report {

enum class ErrorMetric {
  Rmse,          ///< RMSE of V over every pixel that faces the light
  PenumbraRmse,  ///< RMSE of V over the reference's penumbra pixels only
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
};

/// Acceptable: an error at most this many times the lowest error any candidate reached in the
/// situation. On the built-in scenes the techniques' errors span 10× and more; within 2× of the
/// best keeps the family that gets the situation's shadow right and drops the ones whose error
/// shows (hard edges under a soft light, light bleeding, a map stretched over 600 m).
inline constexpr double kAcceptableErrorFactor = 2.0;

enum class Budget { CheapestAcceptable, Balanced, Best };
inline constexpr Budget kBudgets[] = {Budget::CheapestAcceptable, Budget::Balanced, Budget::Best};
const char* budgetName(Budget b);  ///< "cheapest acceptable", "balanced", "best"
const char* budgetKey(Budget b);   ///< "cheapest_acceptable", "balanced", "best" (JSON)

/// What `metric` reads on a row.
double situationError(ErrorMetric metric, const BenchRow& row);
const char* metricName(ErrorMetric metric);  ///< "RMSE", "penumbra RMSE"
const char* metricKey(ErrorMetric metric);   ///< "rmse", "penumbra_rmse" (the results column)

struct SituationPicks {
  const Situation* situation = nullptr;
  std::vector<size_t> candidates;  ///< indices into results.rows
  std::vector<std::string> excluded;  ///< "sdf · uniform: one-off work (...)", one per row left out
  std::vector<size_t> front;       ///< whole-cost Pareto front of the candidates, ascending cost
  double bestError = 0.0, acceptableError = 0.0;
  std::optional<size_t> cheapestAcceptable, balanced, best;  ///< rows; empty when no candidate
  std::optional<size_t> pick(Budget b) const;
};

/// One entry per kSituations entry, in that order; a situation whose scene the run did not
/// measure has no candidates (and no picks).
std::vector<SituationPicks> recommend(const BenchResults& results);

}  // namespace penumbra::report
