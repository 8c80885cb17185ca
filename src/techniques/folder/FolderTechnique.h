#pragma once
// A technique as a folder, loaded at run time (docs/own-technique.md): a description
// (technique.json: id, parameters, the maps it needs) and one GLSL file that defines
// shadowVisibility. Loading registers a filter under the folder's id (registerFilter), so a
// folder technique goes through the registry, the technique value and every tool exactly as a
// built-in does. Its strings (ids, keys, labels, help) live in its description, which is kept
// for the life of the process: the ParamDesc table's string_views never dangle.
#include "frame/Filter.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

/// What a folder technique stores and builds before its visibility pass.
struct FolderMaps {
  int moments = 0;        ///< 0: depth only; 2: (z, z²) RG32F; 4: (z, z², z³, z⁴) RGBA32F
  bool mips = false;      ///< a mip chain of the moments, sampled trilinearly
  bool sat = false;       ///< summed-area tables of the depth's powers (2, or 4 with 4 moments)
  bool minDepth = false;  ///< a min-depth pyramid of the depth map
};

/// One parsed technique.json, with the strings its ParamDesc table points into.
struct FolderDescription {
  std::filesystem::path folder;         ///< absolute, canonical
  std::filesystem::path descriptionFile;///< absolute: folder / technique.json
  std::filesystem::path visibilityFile; ///< absolute: the key its GLSL is compiled under
  std::string id, description;
  FolderMaps maps;
  struct Param {
    std::string key, label, help, unit, define;
    std::vector<std::string> choiceNames;
    std::vector<std::string_view> choices;  ///< views of choiceNames
  };
  std::vector<Param> params;   ///< never resized after descs is made
  std::vector<ParamDesc> descs;
  /// The GLSL constants the visibility program is built with: PARAM_<name> for every runtime
  /// parameter (a read of the technique's uniform block), PARAM_<name>_<choice> per choice, the
  /// maps' switches (PN_TECHNIQUE_*) and the block's size.
  std::vector<std::pair<std::string, std::string>> glslConstants;
  std::vector<int> runtimeSlots;  ///< per parameter: its float in the block, −1 for a compile-time one
  int runtimeCount = 0;
};

/// Parses `folder`/technique.json. Throws a usage Error naming the file and the field at fault.
std::unique_ptr<FolderDescription> readFolderDescription(const std::filesystem::path& folder);

/// A light's instance of a folder technique: its maps and tables, built with the built-ins'
/// own builders (ShadowMapArray, MipBuilder, SatBuilder, MinDepthPyramid).
std::unique_ptr<Filter> makeFolderFilter(const FolderDescription& description);

}  // namespace penumbra
