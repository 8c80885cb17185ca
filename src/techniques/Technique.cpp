// The technique as a value (penumbra/Technique.h): ids, map size and the values of its three
// parameter groups, and the one place that routes a key to one of them.
#include <penumbra/Technique.h>

#include "frame/Projection.h"
#include "techniques/Registry.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

namespace penumbra {
namespace {

std::string prefixOf(std::string_view key) { return std::string(key.substr(0, key.find('.'))); }

bool tableHas(std::span<const ParamDesc> table, std::string_view key) {
  for (const ParamDesc& d : table)
    if (d.key == key) return true;
  return false;
}

bool isIn(const std::vector<std::string>& ids, std::string_view id) {
  for (const std::string& s : ids)
    if (s == id) return true;
  return false;
}

/// Runs f; a usage Error it throws is thrown again with `prefix` before its message.
template <class F>
void prefixed(std::string_view prefix, F&& f) {
  try {
    f();
  } catch (const Error& e) {
    if (prefix.empty() || e.kind() != ErrorKind::Usage) throw;
    throw usageError(fmt::format("{}{}", prefix, e.what()));
  }
}

}  // namespace

Technique::Technique()
    : mProjection("uniform"), mFilter("hard"), mProjectionValues(projectionParams("uniform")),
      mFilterValues(filterParams("hard")), mAddOnValues(makeAddOns()) {}

Technique::Technique(std::string_view projection, std::string_view filter,
                     const std::vector<std::pair<std::string, std::string>>& params)
    : mProjection(projection), mFilter(filter), mProjectionValues(projectionParams(projection)),
      mFilterValues(filterParams(filter)), mAddOnValues(makeAddOns()) {
  for (const auto& [key, value] : params) set(key, std::string_view(value));
}

Technique& Technique::setProjection(std::string_view id) {
  mProjectionValues = Parameterized(projectionParams(id));
  mProjection = std::string(id);
  return *this;
}

Technique& Technique::setFilter(std::string_view id) {
  mFilterValues = Parameterized(filterParams(id));
  mFilter = std::string(id);
  return *this;
}

Technique& Technique::setMapSize(int texels) {
  if (texels < 1 || texels > kMaxMapSizeTexels)
    throw usageError(fmt::format("Technique::mapSize = {}: a map side is 1..{} texels", texels, kMaxMapSizeTexels));
  mMapSize = texels;
  return *this;
}

ParamOwner Technique::owner(std::string_view key) const {
  if (mProjectionValues.hasParam(key)) return ParamOwner::Projection;
  if (mFilterValues.hasParam(key)) return ParamOwner::Filter;
  if (mAddOnValues.hasParam(key)) return ParamOwner::AddOn;
  const std::string prefix = prefixOf(key);
  if (isIn(projectionIds(), prefix) && tableHas(projectionParams(prefix), key)) return ParamOwner::OtherTechnique;
  if (isIn(filterIds(), prefix) && tableHas(filterParams(prefix), key)) return ParamOwner::OtherTechnique;
  return ParamOwner::None;
}

bool Technique::has(std::string_view key) const { return valuesOf(key) != nullptr; }

Parameterized* Technique::valuesOf(std::string_view key) {
  return const_cast<Parameterized*>(static_cast<const Technique&>(*this).valuesOf(key));
}

const Parameterized* Technique::valuesOf(std::string_view key) const {
  switch (owner(key)) {
    case ParamOwner::Projection: return &mProjectionValues;
    case ParamOwner::Filter: return &mFilterValues;
    case ParamOwner::AddOn: return &mAddOnValues;
    case ParamOwner::OtherTechnique:
    case ParamOwner::None: break;
  }
  return nullptr;
}

const ParamDesc& Technique::desc(std::string_view key) const {
  const Parameterized* values = valuesOf(key);
  if (values)
    for (const ParamDesc& d : values->paramDescs())
      if (d.key == key) return d;
  const std::string whose = owner(key) == ParamOwner::OtherTechnique ? fmt::format(" (it is {}'s)", prefixOf(key)) : "";
  throw usageError(fmt::format("unknown parameter '{}' for projection {} and filter {}{}", key, mProjection, mFilter, whose));
}

float Technique::get(std::string_view key) const {
  desc(key);  // throws for a key that is not this technique's
  return valuesOf(key)->param(key);
}

Technique& Technique::set(std::string_view key, std::string_view value) {
  desc(key);
  valuesOf(key)->setParam(key, value);
  return *this;
}

Technique& Technique::set(std::string_view key, float value) {
  desc(key);
  valuesOf(key)->setParam(key, value);
  return *this;
}

std::vector<std::string> Technique::setWhereOwn(const std::vector<std::pair<std::string, std::string>>& params,
                                                std::string_view where) {
  std::vector<std::string> skipped;
  for (const auto& [key, value] : params) {
    const ParamOwner o = owner(key);
    if (o == ParamOwner::OtherTechnique) {  // checked against its own technique's table, then kept for it
      const std::string prefix = prefixOf(key);
      const bool projection = isIn(projectionIds(), prefix);
      for (const ParamDesc& d : projection ? projectionParams(prefix) : filterParams(prefix))
        if (d.key == key) prefixed(where, [&] { parseParamValue(d, value); });
      skipped.push_back(key);
      continue;
    }
    if (o == ParamOwner::None)
      throw usageError(fmt::format("{}no projection, filter or add-on has a parameter '{}'", where, key));
    prefixed(where, [&] { set(key, std::string_view(value)); });
  }
  return skipped;
}

Technique Technique::forLight(const LightShadowSettings& settings, std::string_view where) const {
  Technique t = *this;
  const std::string at = where.empty() ? std::string() : std::string(where) + ": ";
  if (!settings.projection.empty() && settings.projection != t.mProjection)
    prefixed(at + "LightShadowSettings::projection: ", [&] { t.setProjection(settings.projection); });
  if (!settings.filter.empty() && settings.filter != t.mFilter)
    prefixed(at + "LightShadowSettings::filter: ", [&] { t.setFilter(settings.filter); });
  if (settings.mapSize != 0) {
    if (settings.mapSize < 1 || settings.mapSize > kMaxMapSizeTexels)
      throw usageError(fmt::format("{}LightShadowSettings::mapSize = {}: a map side is 1..{} texels", at, settings.mapSize,
                                   kMaxMapSizeTexels));
    t.mMapSize = settings.mapSize;
  }
  t.setWhereOwn(settings.params, at + "LightShadowSettings::params: ");
  return t;
}

std::string Technique::problemWith(const Light& light) const {
  const std::string kind = lightTypeName(light.type);
  if (const std::string why = projectionIncompatibility(mProjection, light); !why.empty())
    return fmt::format("Technique::projection \"{}\" cannot shadow a {} light: {}", mProjection, kind, why);
  if (const std::string why = filterIncompatibility(mFilter, mProjection, light); !why.empty())
    return fmt::format("Technique::filter \"{}\" with projection \"{}\" cannot shadow a {} light: {}", mFilter, mProjection, kind, why);
  if (mAddOnValues.paramInt("translucent.shadows") != 0 && filterShadowsThroughTranslucent(mFilter, mFilterValues))
    return fmt::format("Technique::filter \"{}\" shadows through translucent casters itself ({}): turn translucent.shadows off "
                       "(both would tint V)", mFilter, "msm.translucent=on");
  // The add-on draws whole maps of the projection's views: under a paged projection that is a
  // map of the virtual size per level (12 × 8192² ran out of GL memory), and the pages do not
  // take stochastic's dither (the panes shadowed as opaque).
  if (mAddOnValues.paramInt("translucent.shadows") != 0 && makeProjection(*this)->pageLayout())
    return fmt::format("Technique::projection \"{}\" pages its maps, which translucent.shadows cannot follow (its transmittance "
                       "map would be whole maps of the virtual size; stochastic's dither does not reach the pages): use a "
                       "projection with whole maps (csm for a sun)",
                       mProjection);
  return {};
}

std::vector<std::pair<std::string, std::string>> Technique::changedParams() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Parameterized* values : {&mProjectionValues, &mFilterValues, &mAddOnValues})
    for (const ParamDesc& d : values->paramDescs())
      if (values->param(d.key) != d.def) out.emplace_back(std::string(d.key), formatParamValue(d, values->param(d.key)));
  return out;
}

std::string Technique::text() const {
  std::string out = fmt::format("{} × {}, {}² maps", mProjection, mFilter, mMapSize);
  for (const auto& [key, value] : changedParams()) out += fmt::format(", {}={}", key, value);
  return out;
}

bool Technique::operator==(const Technique& other) const {
  return mProjection == other.mProjection && mFilter == other.mFilter && mMapSize == other.mMapSize &&
         mProjectionValues.sameValues(other.mProjectionValues) && mFilterValues.sameValues(other.mFilterValues) &&
         mAddOnValues.sameValues(other.mAddOnValues);
}

}  // namespace penumbra
