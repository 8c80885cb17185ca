// penumbra tune: a search over one scene's techniques' parameters and map size for the most
// accurate configuration within a cost budget (or the cheapest within an error target), measured
// against the reference on this machine; writes tune.json and tune.html (docs/tune.md).
#include "Commands.h"
#include "Common.h"

#include "platform/Context.h"
#include "report/TuneReport.h"
#include "tuner/TuneRunner.h"
#include "tuner/TuneSearch.h"
#include "tuner/TuneShards.h"

#include <penumbra/Error.h>
#include <penumbra/Reference.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace penumbra::app {
namespace {

// The bounds of tune's numeric options: each far above any useful value, so that only a typo
// (or NaN, infinity, a negative) is refused.
constexpr double kMaxBudgetMs = 1e6;      // a whole frame's shadow cost in milliseconds
constexpr double kMaxBudgetMiB = 1e9;     // MiB of GPU memory
constexpr double kMaxErrorTarget = 100;   // the objectives: RMSE in [0, 1], leak in %
constexpr double kMaxTuneMinutes = 1e6;   // about two years

}  // namespace

void addTuneCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    TechniqueOptions technique;  // --size, --shadow-map (the defaults of compare)
    std::vector<std::string> scenes, cameras, filters, projections, params;
    std::string aggregate = "worst", cost = "measured";
    std::optional<double> budgetMs, budgetMb, maxError;
    std::string objective = "rmse";
    double maxMinutes = 10.0;
    int samples = ReferenceOptions{}.samples;
    int candidates = 24;
    uint64_t seed = 1;
    std::string out = "tune";
    std::optional<std::string> shard;
    std::vector<std::string> merge;
    bool json = false, noCache = false, allowArtifacts = false;
  };
  auto o = std::make_shared<Options>();
  o->technique.referenceBvh = true;  // tune traces the reference
  CLI::App* sub = app.add_subcommand(
      "tune", "search a technique's parameters and maps for the most accurate configuration within a cost budget "
              "on one or several views; write tune.json and tune.html");
  sub->add_option("--scene", o->scenes,
                  "built-in scene name (penumbra list), scene .json file or model file; several (repeated or "
                  "comma-separated): every configuration is measured on each")
      ->required()->delimiter(',');
  sub->add_option("--camera", o->cameras,
                  "a view, as compare's: X,Y,Z:TX,TY,TZ[:FOV]; repeatable: each scene is seen from each camera "
                  "(default: each scene's own)");
  sub->add_option("--aggregate", o->aggregate,
                  "with several views, a configuration's error and cost: worst (the highest of the views') or mean")
      ->capture_default_str();
  sub->add_option("--cost", o->cost,
                  "what the search ranks cost by: measured (whole shadow cost, median ms on this machine; noisy) or "
                  "model (memory written + taps read per frame, millions: the same on every machine and run, so shards, "
                  "merges and reruns give the same front; the budget is then the default's own work)")
      ->capture_default_str();
  sub->add_option("--params", o->params,
                  "search only these keys, comma-separated (parameter keys, shadow.mapSize, shadow.budgetTexels); the "
                  "rest stays at the default. csm.cascades without shadow.budgetTexels keeps the default's map memory")
      ->delimiter(',');
  sub->add_option("--filters", o->filters, "filter ids or technique folders to tune, comma-separated (default: the scene's own)")
      ->delimiter(',')
      ->transform(techniqueFolderFilter());
  sub->add_option("--projections", o->projections, "projection ids, comma-separated (default: the scene's own)")
      ->delimiter(',');
  sub->add_option("--budget-ms", o->budgetMs,
                  "whole shadow cost per frame (shadow + prefilter + visibility, median ms on this machine) at most this "
                  "(default: the default configuration's own cost; with several techniques the dearest default's; with "
                  "--objective acne none)")
      ->check(finiteNumber(0.0, kMaxBudgetMs, true));
  sub->add_option("--budget-mb", o->budgetMb, "GPU memory the technique keeps, at most this many MiB")
      ->check(finiteNumber(0.0, kMaxBudgetMiB, true));
  sub->add_option("--max-error", o->maxError,
                  "an error target instead: the cheapest configuration whose objective is at most this")
      ->check(finiteNumber(0.0, kMaxErrorTarget));
  sub->add_option("--objective", o->objective,
                  "what the error is: rmse (every lit pixel), penumbra_rmse (the reference's penumbra only), leak "
                  "(% of pixels too bright), acne (the filter's bias parameters only: acne, over-darkening where the "
                  "reference is fully lit, at most 0.1 %, then the least leak in the reference's umbra, i.e. shadows "
                  "detached from their casters, then the smallest bias)")
      ->capture_default_str();
  sub->add_flag("--allow-artifacts", o->allowArtifacts,
                "let the pick raise acne above 0.1 % (or the default's own) and umbra leak (detached shadows) above the "
                "default's; without it every pick keeps both, as --objective acne does");
  sub->add_option("--max-minutes", o->maxMinutes,
                  "time for the whole run: the coordinate descent stops early when its next round would pass it (the "
                  "screen, full-size and confirm stages always run)")
      ->capture_default_str()->check(finiteNumber(0.0, kMaxTuneMinutes, true));
  sub->add_option("--size", o->technique.size, "full image size WxH, as compare (the screen stage uses a quarter of each side, the shorter at least 32)")
      ->capture_default_str();
  sub->add_option("--shadow-map", o->technique.shadowMapSize,
                  "the default configuration's map size, searched over powers of two from half to twice it, or with a "
                  "map count (csm.cascades) the maps' texels in all (compare's --shadow-budget) from a quarter to four "
                  "times the default's, never below the least the command line takes (not with --objective acne; "
                  "default: the first scene's own, as compare); " + mapSizeLimitText())
      ->check(mapSizeOption());
  sub->add_option("--samples", o->samples, "reference light samples per pixel (as compare)")
      ->capture_default_str()->check(CLI::Range(1, kMaxReferenceSamples));
  sub->add_option("--candidates", o->candidates, "Latin-hypercube candidates per technique in the screen stage")
      ->capture_default_str()->check(CLI::Range(1, 1000));
  sub->add_option("--seed", o->seed, "seed of the candidates")->check(unsignedNumber())->capture_default_str();
  sub->add_option("--out", o->out,
                  "output folder: tune.json, tune.html, evaluations.jsonl (every configuration measured: a rerun with "
                  "the same folder resumes from it)")
      ->capture_default_str();
  sub->add_option("--shard", o->shard,
                  "K/N: measure only the K-th of N shares of the screen stage into OUT/evaluations.jsonl and stop (run "
                  "the N shares anywhere with the same options, then --merge their folders)");
  sub->add_option("--merge", o->merge,
                  "DIR..., the --out folders of --shard runs: gather their evaluations.jsonl into OUT and go on from them "
                  "(the rest of the search runs here)")
      ->expected(1, -1);
  sub->add_flag("--json", o->json, "print tune.json on stdout instead of the summary (the progress stays on stderr)");
  sub->add_flag("--no-cache", o->noCache, "recompute the references even if cached ones exist");
  sub->add_flag("--verbose", o->technique.verbose, "one line per configuration on stderr");
  commands.push_back({sub, [o] {
    report::TuneRequest req;
    req.objective = report::parseObjective(o->objective);
    req.aggregate = report::parseAggregate(o->aggregate);
    req.cost = report::parseCost(o->cost);
    if (o->budgetMs && o->maxError)
      throw usageError("--budget-ms and --max-error: give a cost budget or an error target, not both");
    if (o->budgetMs && req.cost == report::TuneCost::Model)
      throw usageError("--budget-ms with --cost model: the model counts work, not milliseconds (its budget is the default's work)");
    // The views: each scene from each camera; usage errors before any GL.
    for (const std::string& scene : o->scenes) {
      if (o->cameras.empty()) req.views.push_back({.scene = scene, .camera = ""});
      for (const std::string& camera : o->cameras) req.views.push_back({.scene = scene, .camera = camera});
    }
    for (const report::TuneView& v : req.views) {
      TechniqueOptions t = o->technique;
      t.scene = v.scene;
      if (!v.camera.empty()) t.camera = v.camera;
      (void)makeSetup(t);
    }
    // The first scene's own choices and the defaults of compare.
    o->technique.scene = req.views.front().scene;
    const Setup scene = makeSetup(o->technique);
    req.filters = o->filters.empty() ? std::vector<std::string>{scene.technique.filter()} : o->filters;
    req.projections = o->projections.empty() ? std::vector<std::string>{scene.technique.projection()} : o->projections;
    // --params: each key is searched somewhere, and each technique has a key to search. Unknown
    // ids are usage Errors naming them (filterParams, projectionParams).
    const auto inTable = [](std::span<const ParamDesc> table, const std::string& key) {
      return std::any_of(table.begin(), table.end(), [&](const ParamDesc& d) { return d.key == key; });
    };
    const auto mapKey = [](const std::string& key) { return key == report::kMapSizeKey || key == report::kMapBudgetKey; };
    const auto anyHas = [&](const std::vector<std::string>& ids, auto params, const std::string& key) {
      return std::any_of(ids.begin(), ids.end(), [&](const std::string& id) { return inTable(params(id), key); });
    };
    const auto filterTable = [](const std::string& id) { return filterParams(id); };
    const auto projectionTable = [](const std::string& id) { return projectionParams(id); };
    for (const std::string& f : req.filters) (void)filterParams(f);
    for (const std::string& p : req.projections) (void)projectionParams(p);
    for (const std::string& key : o->params)
      if (!mapKey(key) && !anyHas(req.filters, filterTable, key) && !anyHas(req.projections, projectionTable, key))
        throw usageError(fmt::format("--params {}: not a parameter of --filters {} or --projections {} (penumbra list shows "
                                     "their keys), nor {} or {}",
                                     key, joinNames(req.filters, ","), joinNames(req.projections, ","), report::kMapSizeKey,
                                     report::kMapBudgetKey));
    if (!o->params.empty() && std::none_of(o->params.begin(), o->params.end(), mapKey))
      for (const std::string& f : req.filters)
        for (const std::string& p : req.projections)
          if (std::none_of(o->params.begin(), o->params.end(),
                           [&](const std::string& k) { return inTable(filterParams(f), k) || inTable(projectionParams(p), k); }))
            throw usageError(fmt::format("tune: {} · {} has no parameter to search among --params {} (give one of its keys, or "
                                         "tune it apart)",
                                         f, p, joinNames(o->params, ",")));
    req.settings.width = scene.render.width;
    req.settings.height = scene.render.height;
    req.settings.shadowMapSize = o->technique.shadowMapSize;
    req.settings.referenceSamples = o->samples;
    req.settings.useCache = !o->noCache;
    req.settings.warmupFrames = 1;
    req.searchKeys = o->params;
    req.budget = {.costMs = o->budgetMs, .memoryMiB = o->budgetMb, .maxError = o->maxError};
    req.maxMinutes = o->maxMinutes;
    req.allowArtifacts = o->allowArtifacts;
    req.candidates = o->candidates;
    req.seed = o->seed;
    req.outDir = o->out;
    req.verbose = o->technique.verbose;
    if (o->shard) req.shard = report::parseShard(*o->shard);
    if (o->shard && !o->merge.empty()) throw usageError("--shard and --merge: a shard measures, a merge gathers; not both");

    checkOutputDir("--out", o->out);
    std::filesystem::create_directories(req.outDir);
    if (!o->merge.empty()) {
      const std::vector<std::filesystem::path> dirs(o->merge.begin(), o->merge.end());
      const size_t added = report::mergeEvaluations(dirs, req.outDir);
      std::fprintf(stderr, "penumbra tune: merged %zu evaluations from %zu folders into %s\n", added, dirs.size(),
                   (req.outDir / "evaluations.jsonl").string().c_str());
    }
    gl::HeadlessContext context({.debug = gl::kDebugBuild, .verbose = o->technique.verbose});
    checkImageFits(context, req.settings.width, req.settings.height, kCompareHostBytesPerPixel);
    const report::TuneSetupFactory factory = [](const report::BenchConfig& c, const std::string& camera) {
      return benchSetupFactory(camera.empty() ? std::nullopt : std::optional<std::string>(camera))(c);
    };
    report::TuneResults res = report::runTune(context, req, factory);
    if (req.shard) {
      std::printf("shard %d/%d: %zu configurations measured (%zu resumed) in %.0f s into %s\n", req.shard->index,
                  req.shard->count, res.evaluations, res.resumed, res.seconds,
                  (req.outDir / "evaluations.jsonl").string().c_str());
      return 0;
    }
    res.machine.command = commandLine();
    report::writeTuneOutputs(req.outDir, res);
    if (o->json) {
      std::printf("%s\n", report::tuneJson(res).dump(2).c_str());
      return res.recommended ? 0 : 1;
    }
    const report::TuneRow* def = report::tuneDefaultFor(res);
    const auto line = [&](const char* what, const report::TuneRow& r) {
      const std::string spread = r.rounds > 0 ? fmt::format(" ({:.3f}-{:.3f} over {} interleaved rounds; {:.2f}x the budget's default, "
                                                            "p90 {:.2f}x)",
                                                            r.costP10Ms, r.costP90Ms, r.rounds, r.costRatio.median, r.costRatio.p90)
                                              : std::string();
      std::printf("  %-12s %s %.4g  RMSE %.4f  penumbra RMSE %.4f  leak %.2f%% (umbra %.3f%%)  acne %.3f%%  cost %.3f ms%s  "
                  "work %.4g Mops  memory %.1f MiB\n",
                  what, report::objectiveKey(req.objective), r.error, r.metrics.rmse, r.metrics.penumbraRmse,
                  r.metrics.leakPct, r.metrics.umbraLeakPct, r.metrics.acnePct, r.costMs, spread.c_str(), r.workM, r.memoryMiB);
    };
    std::printf("tune %s: %zu configurations measured (%zu resumed) in %.0f s on %s (%s); budget %.4g %s%s\n",
                report::tuneViewsText(req).c_str(), res.evaluations, res.resumed, res.seconds, res.machine.glRenderer.c_str(),
                res.machine.clock.c_str(), res.budget, req.cost == report::TuneCost::Model ? "Mops (--cost model)" : "ms",
                o->budgetMb ? fmt::format(", {:.1f} MiB", *o->budgetMb).c_str() : "");
    if (!res.recommended) {
      std::printf("no configuration fits the budget; the front is in %s\n", (req.outDir / "tune.html").string().c_str());
      if (def) line("default", *def);
      return 1;
    }
    const report::TuneRow& rec = res.confirmed[*res.recommended];
    line("recommended", rec);
    if (def) line("default", *def);
    std::printf("set:      %s\n", report::tuneSetLine(rec).c_str());
    if (rec.views.size() > 1) {
      std::printf("views (%s of each row's):\n", report::aggregateKey(req.aggregate));
      for (size_t v = 0; v < rec.views.size(); ++v)
        std::printf("  %s %.4g (default %.4g)\n  compare:  %s\n", report::objectiveKey(req.objective), rec.views[v].error,
                    def && v < def->views.size() ? def->views[v].error : 0.0, rec.views[v].command.c_str());
    } else {
      std::printf("compare:  %s\n", rec.command.c_str());
    }
    std::printf("scene file:\n%s\nfront (%zu configurations) and chart: %s\n", report::tuneSceneSnippet(rec).c_str(),
                res.front.size(), (req.outDir / "tune.html").string().c_str());
    return 0;
  }});
}

}  // namespace penumbra::app
