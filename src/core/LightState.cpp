#include "core/LightState.h"

#include "base/Hash.h"
#include "techniques/Registry.h"

namespace penumbra::core {

bool LightState::adopt(const Technique& merged) {
  // A filter whose maker was replaced since (a technique folder's description reloaded) is made anew.
  const uint64_t revision = filterRevision(merged.filter());
  const bool newFilter = !filter || merged.filter() != technique.filter() || revision != filterMadeAt;
  filterMadeAt = revision;
  const bool newProjection = !projection || merged.projection() != technique.projection() ||
                             !merged.projectionValues().sameValues(technique.projectionValues());
  technique = merged;
  if (newFilter) filter = makeFilter(technique.filter());
  if (newProjection) projection = makeProjection(technique);
  return newFilter;
}

uint64_t accumulationKey(const Technique& technique) {
  Hasher h;
  h.text(technique.projection());
  h.text(technique.filter());
  h.value(technique.mapSize());
  for (const Parameterized* values : {&technique.projectionValues(), &technique.filterValues(), &technique.addOnValues()})
    for (const ParamDesc& d : values->paramDescs())
      if (!d.key.starts_with("temporal.")) h.value(values->param(d.key));
  return h.digest();
}

}  // namespace penumbra::core
