#pragma once
// A shadow technique as a value (docs/design.md, "A technique and a light's state"): which
// projection places the light's views (the aliasing axis), which filter turns its maps into V
// (the softness axis), the maps' size, and the value of every parameter: the projection's, the
// filter's and the add-ons' (contact shadows, temporal accumulation). It is copied, compared and
// printed like any value; Shadows makes each light's state from it, with the light's own settings
// merged in (forLight). The ids and parameter tables come from the registry (penumbra list shows
// them): parameters are declared once, and every key is routed here (owner) and nowhere else.
#include <penumbra/Light.h>
#include <penumbra/Params.h>

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

/// The ids of the projections and filters this build has, in the registry's order.
std::vector<std::string> projectionIds();
std::vector<std::string> filterIds();
/// One sentence on what the projection or filter does; throws a usage Error for an unknown id.
std::string_view projectionDescription(std::string_view id);
std::string_view filterDescription(std::string_view id);
/// What filter `id` does with a translucent caster (CasterMesh::transmittance): draws it as
/// opaque, ignores it, or shadows through it (with the translucent.* add-on).
std::string_view filterTranslucentCasters(std::string_view id);
/// Its parameter table (ParamDesc); throws a usage Error for an unknown id.
std::span<const ParamDesc> projectionParams(std::string_view id);
std::span<const ParamDesc> filterParams(std::string_view id);

/// Loads a technique folder (docs/own-technique.md: technique.json and its GLSL) and registers
/// it as a filter under the id its description gives; returns that id. Loading a folder again
/// returns its id; its description is read once per process (its GLSL at every compile). Throws
/// a usage Error naming the file and the field at fault, or an id another technique has.
std::string loadTechniqueFolder(const std::filesystem::path& folder);
/// The filter a --filter argument names: a registered id as it is; a path (it holds a '/', or
/// names a folder) loaded with loadTechniqueFolder; anything else as it is (unknown ids are
/// refused where they are used).
std::string resolveFilter(std::string_view text);
/// The folder a filter was loaded from (absolute); empty for a built-in or a registered filter.
std::filesystem::path techniqueFolder(std::string_view filterId);
/// What names the filter on a command line in another process: its folder for a technique
/// folder's id (a printed command loads it again), else the id.
std::string filterArgument(std::string_view filterId);
/// Reads a loaded folder's technique.json again and puts it in place of the loaded one under the
/// same id: techniques made after this take its parameters, maps and GLSL constants, and every
/// light running the id makes its filter anew (techniques made before keep pointing at the old
/// description, which stays alive). Throws a usage Error naming the file and the field at fault,
/// a changed id, or a folder never loaded; the loaded description stays then. Returns the id.
std::string reloadTechniqueFolder(const std::filesystem::path& folder);
/// Puts back the description the last reloadTechniqueFolder() of `folder` replaced (for a caller
/// whose techniques could not take the new one). Throws a usage Error when there is none.
void restorePreviousTechniqueFolder(const std::filesystem::path& folder);
/// The GLSL files of every technique folder loaded: what a viewer watches to reload.
std::vector<std::filesystem::path> techniqueFolderFiles();
/// The technique.json of every technique folder loaded: what a viewer watches to reload.
std::vector<std::filesystem::path> techniqueFolderDescriptions();

/// A parameter group any filter can take: a pass the core runs after the filter's own.
struct AddOnGroup {
  std::string_view label;             ///< "Contact shadows"
  std::span<const ParamDesc> params;  ///< keys "prefix.name"
};
/// Every add-on group: contact shadows ("contact.*", docs/contact.md) and temporal accumulation
/// ("temporal.*", docs/temporal.md).
std::span<const AddOnGroup> addOnGroups();

/// Where a parameter key belongs, seen from one technique.
enum class ParamOwner {
  Projection,      ///< its projection's
  Filter,          ///< its filter's
  AddOn,           ///< an add-on's ("contact.*", "temporal.*")
  OtherTechnique,  ///< another projection's or filter's ("csm.cascades" for a uniform technique)
  None,            ///< no technique has it
};

/// Texels per side of a technique's maps unless it says otherwise (Technique::mapSize).
inline constexpr int kDefaultMapSize = 2048;

class Technique {
public:
  /// The uniform projection and the hard filter, every parameter at its default.
  Technique();
  /// By id, every parameter at its default, then `params` ("key" → "value") set in order.
  /// Throws a usage Error naming an unknown id, a key that is not this technique's, or a value
  /// out of range.
  Technique(std::string_view projection, std::string_view filter,
            const std::vector<std::pair<std::string, std::string>>& params = {});

  const std::string& projection() const { return mProjection; }
  const std::string& filter() const { return mFilter; }
  /// Another projection (or filter): its parameters start at their defaults; the rest stays.
  /// Throws a usage Error for an unknown id.
  Technique& setProjection(std::string_view id);
  Technique& setFilter(std::string_view id);

  /// Texels per side of each of a light's maps (a light's LightShadowSettings::mapSize wins; a
  /// budget, ShadowFrameInputs::mapBudgetTexels, may grant less). Default kDefaultMapSize.
  int mapSize() const { return mMapSize; }
  /// Throws a usage Error outside [kMinMapSizeTexels, kMaxMapSizeTexels].
  Technique& setMapSize(int texels);

  /// Where `key` belongs: the one place that routes a parameter key.
  ParamOwner owner(std::string_view key) const;
  /// True when the key is this technique's own (projection, filter or add-on).
  bool has(std::string_view key) const;
  /// Its description; throws a usage Error when the key is not this technique's.
  const ParamDesc& desc(std::string_view key) const;
  float get(std::string_view key) const;
  int getInt(std::string_view key) const { return static_cast<int>(get(key)); }
  /// Sets one of this technique's parameters: a number, or a choice's name. Throws a usage Error
  /// naming the key for one that is not this technique's (another technique's key included) or
  /// a value out of range.
  Technique& set(std::string_view key, std::string_view value);
  Technique& set(std::string_view key, float value);
  /// Sets the keys that are this technique's and returns those that belong to another technique
  /// (skipped: they apply when that technique runs; their values are checked all the same);
  /// throws a usage Error, prefixed with `where`, for a key of no technique or a bad value.
  std::vector<std::string> setWhereOwn(const std::vector<std::pair<std::string, std::string>>& params,
                                       std::string_view where = {});

  /// The technique a light runs: this one with the light's own settings merged in (its
  /// projection and filter, its map size, its parameters; keys of other techniques skipped).
  /// Throws a usage Error naming `where` (e.g. "light 2") and the LightShadowSettings field.
  Technique forLight(const LightShadowSettings& settings, std::string_view where) const;
  /// Empty when this technique can shadow `light`; otherwise why not (a cascaded projection and
  /// a point light, a filter that needs what is not installed), naming the Technique field.
  std::string problemWith(const Light& light) const;

  /// The values of each part, over its parameter table.
  const Parameterized& projectionValues() const { return mProjectionValues; }
  const Parameterized& filterValues() const { return mFilterValues; }
  const Parameterized& addOnValues() const { return mAddOnValues; }

  /// Parameters whose value differs from the default, as "key" → "value" (the form --set,
  /// scene files and the constructor read back).
  std::vector<std::pair<std::string, std::string>> changedParams() const;
  /// "csm × pcss, 2048² maps, pcss.blockerSamples=16": ids, map size and changed parameters.
  std::string text() const;

  bool operator==(const Technique& other) const;

private:
  Parameterized* valuesOf(std::string_view key);
  const Parameterized* valuesOf(std::string_view key) const;

  std::string mProjection, mFilter;
  int mMapSize = kDefaultMapSize;
  Parameterized mProjectionValues, mFilterValues, mAddOnValues;
};

}  // namespace penumbra
