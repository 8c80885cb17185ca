#include "core/LightState.h"

#include "base/Hash.h"
#include "shadows/Registry.h"

namespace penumbra::core {

bool LightState::adopt(const Technique& merged) {
  const bool newFilter = !filter || merged.filter() != technique.filter();
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
