#pragma once
// Per-pixel record of a penumbra estimate for the debug views "blocker-depth" and
// "penumbra-width-m" (shared/PenumbraDebug.h; cleared to PN_PENUMBRA_DEBUG_NONE every frame by
// PenumbraDebugImages). Written by the filters that estimate a penumbra from an average blocker
// depth; it never changes V. Points mode (Renderer::visibilityAt) has no pixels: nothing is
// written. In a cascade blend band the second cascade's estimate is the one kept.
#include "common/penumbra.glsl"
#include "common/visibility.glsl"
#include "shared/PenumbraDebug.h"

#ifndef PN_VISIBILITY_POINTS
layout(binding = PN_IMG_BLOCKER_DEPTH, r32f) uniform writeonly image2D i_blockerDepth;
layout(binding = PN_IMG_PENUMBRA_WIDTH, r32f) uniform writeonly image2D i_penumbraWidth;
#endif

// A blocker at linear depth `blockerDepth` was found for the receiver s in `view`: stores that
// depth and the similar-triangles penumbra width (m) before any filter-radius clamp.
void recordPenumbra(SurfacePoint s, int view, float blockerDepth, float lightSize) {
#ifndef PN_VISIBILITY_POINTS
  float widthM = penumbraWidthM(view, lightDepth(view, s.ws), blockerDepth, lightSize);
  imageStore(i_blockerDepth, s.pixel, vec4(blockerDepth));
  imageStore(i_penumbraWidth, s.pixel, vec4(widthM));
#endif
}

// The receiver s was searched and no blocker was found (or it lies outside the map).
void recordNoBlocker(SurfacePoint s) {
#ifndef PN_VISIBILITY_POINTS
  imageStore(i_blockerDepth, s.pixel, vec4(PN_PENUMBRA_DEBUG_NONE));
  imageStore(i_penumbraWidth, s.pixel, vec4(PN_PENUMBRA_DEBUG_NONE));
#endif
}
