#pragma once
// Enum values shared by C++ and GLSL. C++ enum classes are defined from these macros.

#define PN_LIGHT_SUN 0
#define PN_LIGHT_SPOT 1
#define PN_LIGHT_POINT 2

// hard.bias
#define PN_BIAS_NONE 0
#define PN_BIAS_CONSTANT 1
#define PN_BIAS_SLOPE 2
#define PN_BIAS_NORMAL 3
#define PN_BIAS_PLANE 4

// Debug views of the lit pass
#define PN_VIEW_SHADED 0
#define PN_VIEW_VISIBILITY 1
#define PN_VIEW_CASCADES 2       // shading tinted by the cascade (view) each pixel uses; blends mixed
#define PN_VIEW_TEXEL_DENSITY 3  // screen pixels per shadow-map texel as a heatmap (shared/DensityRamp.h)
