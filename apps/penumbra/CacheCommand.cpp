// penumbra cache: where the cache folder is, how full, what it holds (least recently used
// first: the next to be evicted), and the means to empty or trim it now.
#include "Commands.h"
#include "Common.h"

#include <penumbra/Error.h>
#include <penumbra/Files.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace penumbra::app {
namespace {

constexpr double kBytesPerMiB = 1024.0 * 1024.0;

std::chrono::system_clock::time_point toSystem(std::filesystem::file_time_type t) {
  return std::chrono::time_point_cast<std::chrono::system_clock::duration>(std::chrono::file_clock::to_sys(t));
}

/// Local date and time to the second.
std::string localTime(std::filesystem::file_time_type t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(toSystem(t));
  std::tm local{};
  localtime_r(&seconds, &local);
  char text[32];
  return std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &local) ? text : "?";
}

std::uintmax_t totalBytes(const std::vector<CacheEntry>& entries) {
  std::uintmax_t total = 0;
  for (const CacheEntry& e : entries) total += e.bytes;
  return total;
}

}  // namespace

void addCacheCommand(CLI::App& app, std::vector<Command>& commands) {
  struct Options {
    bool clear = false, json = false;
    std::optional<std::uintmax_t> cacheMaxMb;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "cache",
      fmt::format("show the cache folder (ray-traced references, sdf bakes): where it is, its cap, its size and its "
                  "entries, least recently used first (the next to be evicted); or empty or trim it. The folder is "
                  "$PENUMBRA_CACHE, else $XDG_CACHE_HOME/penumbra, else ~/.cache/penumbra; its cap is ${} MiB, else "
                  "{} MiB. Entries are files named <kind>-<key>.bin, and the temporary files of writes whose "
                  "process is gone (interrupted: listed and removed first); nothing else there is touched",
                  kCacheMaxEnv, kDefaultCacheMaxMiB));
  CLI::Option* clear = sub->add_flag("--clear", o->clear, "remove every entry");
  addCacheCapOption(*sub, o->cacheMaxMb, "now");
  sub->get_option("--cache-max-mb")->excludes(clear);
  sub->add_flag("--json", o->json, "print one JSON object on stdout instead of the listing");
  commands.push_back({sub, [o] {
    const std::filesystem::path dir = defaultCacheDir();
    if (dir.empty()) throw Error("no cache folder: set PENUMBRA_CACHE (or HOME) to say where it is");
    const std::uintmax_t cap = defaultCacheMaxBytes();  // a malformed variable is a usage error even here
    checkCacheFolder(dir);
    std::vector<CacheEntry> removed;
    std::vector<std::string> failures;
    if (o->clear) removed = trimCache(dir, 0, &failures);
    else if (o->cacheMaxMb) removed = trimCache(dir, *cacheCapBytes(o->cacheMaxMb), &failures);
    // What could not be removed stays: the run fails, saying what is left and why.
    if (!failures.empty())
      throw Error(fmt::format("{}: removed {} entries, but {} cannot be removed (the first: {})", dir.string(), removed.size(),
                              failures.size(), failures.front()));
    const std::vector<CacheEntry> entries = listCacheEntries(dir);

    if (o->json) {
      nlohmann::json j;
      j["folder"] = dir.string();
      j["max_bytes"] = cap;
      j["bytes"] = totalBytes(entries);
      j["entries"] = nlohmann::json::array();
      for (const CacheEntry& e : entries)
        j["entries"].push_back({{"name", e.path.filename().string()},
                                {"bytes", e.bytes},
                                {"last_use_unix_s", std::chrono::duration_cast<std::chrono::seconds>(
                                                        toSystem(e.lastUse).time_since_epoch()).count()},
                                {"interrupted", e.interrupted}});
      j["removed"] = nlohmann::json::array();
      for (const CacheEntry& e : removed) j["removed"].push_back(e.path.filename().string());
      std::printf("%s\n", j.dump(2).c_str());
      return 0;
    }
    if (!removed.empty() || o->clear || o->cacheMaxMb)
      std::printf("removed %zu entries (%.1f MiB)\n", removed.size(), static_cast<double>(totalBytes(removed)) / kBytesPerMiB);
    std::printf("folder   %s\ncap      %.0f MiB\nsize     %.1f MiB in %zu entries\n", dir.string().c_str(),
                static_cast<double>(cap) / kBytesPerMiB, static_cast<double>(totalBytes(entries)) / kBytesPerMiB,
                entries.size());
    if (!entries.empty()) std::printf("entries, least recently used first:\n");
    for (const CacheEntry& e : entries)
      std::printf("  %-28s %10.2f MiB  %s %s\n", e.path.filename().string().c_str(), static_cast<double>(e.bytes) / kBytesPerMiB,
                  e.interrupted ? "an interrupted write, from" : "last used", localTime(e.lastUse).c_str());
    return 0;
  }});
}

}  // namespace penumbra::app
