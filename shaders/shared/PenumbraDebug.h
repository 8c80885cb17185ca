#pragma once
// The penumbra debug images written by the visibility pass of the filters that estimate a
// penumbra from an average blocker depth (pcss, vssm): image units and the "no blocker" value,
// shared by C++ (src/techniques/PenumbraDebugImages.h) and GLSL (common/penumbra_debug.glsl).
#include "shared/Bindings.h"

// Both images are screen-sized r32f, bound only for the per-pixel visibility pass.
#define PN_IMG_BLOCKER_DEPTH PN_IMG_AUX0   // mean blocker depth: linear light depth in [0,1]
#define PN_IMG_PENUMBRA_WIDTH PN_IMG_AUX1  // estimated penumbra width on the receiver (m)

// Stored in both images where no blocker estimate exists: no blocker found (lit), or the
// pixel was not searched (no geometry, facing away from the light, outside the map). Valid
// values are >= 0, so any negative value means "none".
#define PN_PENUMBRA_DEBUG_NONE (-1.0f)
