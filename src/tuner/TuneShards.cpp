#include "tuner/TuneShards.h"

#include <penumbra/Error.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <charconv>
#include <fstream>
#include <set>

namespace penumbra::report {
namespace {

constexpr const char* kEvaluationsFile = "evaluations.jsonl";

// The key of one evaluations.jsonl line, "" for a line cut short or without one.
std::string lineKey(const std::string& line) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.contains("key") || !j["key"].is_string()) return {};
  return j["key"].get<std::string>();
}

}  // namespace

TuneShard parseShard(std::string_view text) {
  const size_t slash = text.find('/');
  TuneShard s{.index = 0, .count = 0};
  const auto parse = [](std::string_view t, int& out) {
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc() && end == t.data() + t.size();
  };
  if (slash == std::string_view::npos || !parse(text.substr(0, slash), s.index) || !parse(text.substr(slash + 1), s.count) ||
      s.count < 1 || s.index < 1 || s.index > s.count)
    throw usageError(fmt::format("--shard {}: expected K/N with 1 <= K <= N, e.g. 2/4", text));
  return s;
}

size_t mergeEvaluations(std::span<const std::filesystem::path> dirs, const std::filesystem::path& out) {
  std::set<std::string> keys;
  const std::filesystem::path target = out / kEvaluationsFile;
  {
    std::ifstream in(target);
    for (std::string line; std::getline(in, line);) keys.insert(lineKey(line));
  }
  std::ofstream append(target, std::ios::app);
  size_t added = 0;
  for (const std::filesystem::path& dir : dirs) {
    std::ifstream in(dir / kEvaluationsFile);
    if (!in) throw Error(fmt::format("--merge {}: no {} there (the --out of a tune --shard run?)", dir.string(), kEvaluationsFile));
    for (std::string line; std::getline(in, line);) {
      const std::string key = lineKey(line);
      if (key.empty() || !keys.insert(key).second) continue;
      append << line << '\n';
      ++added;
    }
  }
  return added;
}

}  // namespace penumbra::report
