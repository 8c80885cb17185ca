// penumbra list: scenes, projections, filters and every parameter (default, range, help).
#include "Commands.h"
#include "Common.h"

#include "techniques/Registry.h"
#include <penumbra/SceneIO.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace penumbra::app {
namespace {

nlohmann::json paramsJson(std::span<const ParamDesc> descs) {
  nlohmann::json out = nlohmann::json::array();
  for (const ParamDesc& d : descs) {
    nlohmann::json p = {{"key", d.key}, {"label", d.label}, {"help", d.help}};
    if (d.isChoice()) {
      p["default"] = formatParamValue(d, d.def);
      p["choices"] = nlohmann::json::array();
      for (std::string_view c : d.choices) p["choices"].push_back(c);
    } else {
      p["default"] = d.def;
      p["min"] = d.min;
      p["max"] = d.max;
      p["integer"] = d.isInteger();
      p["unit"] = d.unit;
    }
    out.push_back(p);
  }
  return out;
}

void printParams(std::span<const ParamDesc> descs) {
  for (const ParamDesc& d : descs) {
    std::string range;
    if (d.isChoice()) {
      range = joinNames(d.choices, "|");
    } else {
      range = fmt::format("{} .. {} {}", d.min, d.max, d.unit);
    }
    std::printf("    %-28s default %-8s [%s]  %s\n", std::string(d.key).c_str(), formatParamValue(d, d.def).c_str(),
                range.c_str(), std::string(d.help).c_str());
  }
}

}  // namespace

void addListCommand(CLI::App& app, std::vector<Command>& commands) {
  auto json = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand("list", "list scenes, projections, filters and their parameters");
  sub->add_flag("--json", *json, "print one JSON object instead of text");
  auto folders = std::make_shared<std::vector<std::string>>();
  sub->add_option("--filter", *folders, "a technique folder to load and list with the built-in filters, repeatable")
      ->transform(techniqueFolderFilter());
  commands.push_back({sub, [json, folders] {
    (void)folders;  // loaded and registered while the command line was parsed
    nlohmann::json j;
    j["scenes"] = nlohmann::json::array();
    for (const std::string& n : builtinSceneNames()) j["scenes"].push_back({{"name", n}, {"description", builtinSceneDescription(n)}});
    j["scene_params"] = paramsJson(sceneParamDescs());
    j["add_on_params"] = paramsJson(makeAddOns().paramDescs());
    j["projections"] = nlohmann::json::array();
    for (const std::string& id : projectionIds())
      j["projections"].push_back({{"id", id}, {"description", projectionDescription(id)}, {"params", paramsJson(projectionParams(id))}});
    j["filters"] = nlohmann::json::array();
    for (const std::string& id : filterIds())
    {
      nlohmann::json f = {{"id", id},
                          {"description", filterDescription(id)},
                          {"translucent_casters", filterTranslucentCasters(id)},
                          {"params", paramsJson(filterParams(id))}};
      if (const std::filesystem::path folder = techniqueFolder(id); !folder.empty()) f["folder"] = folder.string();
      j["filters"].push_back(f);
    }
    if (*json) {
      std::printf("%s\n", j.dump(2).c_str());
      return 0;
    }
    std::printf("Scenes (--scene NAME, or a .json file):\n");
    for (const std::string& n : builtinSceneNames()) std::printf("  %-10s %s\n", n.c_str(), std::string(builtinSceneDescription(n)).c_str());
    std::printf("\nScene parameters (--set key=value):\n");
    printParams(sceneParamDescs());
    for (const AddOnGroup& g : addOnGroups()) {
      std::printf("\n%s, with any filter (--set key=value):\n", std::string(g.label).c_str());
      printParams(g.params);
    }
    std::printf("\nProjections (--projection ID):\n");
    for (const std::string& id : projectionIds()) {
      std::printf("  %-10s %s\n", id.c_str(), std::string(projectionDescription(id)).c_str());
      printParams(projectionParams(id));
    }
    std::printf("\nFilters (--filter ID):\n");
    for (const std::string& id : filterIds()) {
      std::printf("  %-10s %s\n", id.c_str(), std::string(filterDescription(id)).c_str());
      if (const std::filesystem::path folder = techniqueFolder(id); !folder.empty())
        std::printf("             (technique folder %s)\n", folder.string().c_str());
      std::printf("  %-10s translucent casters: %s\n", "", std::string(filterTranslucentCasters(id)).c_str());
      printParams(filterParams(id));
    }
    return 0;
  }});
}

}  // namespace penumbra::app
