#pragma once
// Enum values shared by C++ and GLSL. C++ enum classes are defined from these macros.

#define PN_LIGHT_SUN 0
#define PN_LIGHT_SPOT 1

// How a frame's shadow views project (PN_VIEW_KIND, when every view of the frame is of one kind)
#define PN_VIEW_KIND_ORTHO 0        // orthographic: texels the same size everywhere
#define PN_VIEW_KIND_PERSPECTIVE 1  // a spot light's frustum: texels grow with distance
#define PN_VIEW_KIND_WARPED 2       // psm/tsm: a projective warp, texel size from the derivatives

// hard.bias
#define PN_BIAS_NONE 0
#define PN_BIAS_CONSTANT 1
#define PN_BIAS_SLOPE 2
#define PN_BIAS_NORMAL 3

// Debug views of the lit pass
#define PN_VIEW_SHADED 0
#define PN_VIEW_VISIBILITY 1
#define PN_VIEW_CASCADES 2       // shading tinted by the cascade (view) each pixel uses; blends mixed
#define PN_VIEW_TEXEL_DENSITY 3  // screen pixels per shadow-map texel as a heatmap (shared/DensityRamp.h)
