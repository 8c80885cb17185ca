#include "report/FrameComparison.h"

namespace penumbra::report {

FrameComparison compareFrame(Renderer& renderer, const ReferenceResult& ref, bool images) {
  FrameComparison c;
  c.visibility = renderer.readVisibility();
  c.metrics = compareVisibility(c.visibility, ref.visibility, ref.litMask);
  if (images) {
    c.technique = renderer.readColor();
    c.reference = renderer.shadeWithVisibility(ref.visibility);
    c.heatmap = errorHeatmap(c.visibility, ref.visibility, ref.litMask, ref.width, ref.height, &c.technique, kLabHeatmap);
  }
  return c;
}

}  // namespace penumbra::report
