#pragma once
// The viewer's display pass (src/viewer/DebugDisplay.cpp, shaders/passes/viewer_*.glsl):
// shows any texture (colour output, visibility, G-buffer, a filter's maps) in a window region,
// a chosen channel/layer/level mapped to grey or a colour map over a fixed or measured range.
#include "shared/Cpp.h"

// Bindings, used only while the viewer draws (after the frame: nothing else is bound then).
#define PN_VIEWER_TEX_SOURCE 0     // the texture shown
#define PN_VIEWER_UBO_DISPLAY 3    // ViewerDisplayUniforms
#define PN_VIEWER_SSBO_RANGE 3     // uvec2: order-preserving encoded min and max of the shown values

// Source kinds: compile-time variants (PN_VIEWER_SOURCE)
#define PN_VIEWER_SOURCE_2D 0
#define PN_VIEWER_SOURCE_2D_ARRAY 1
#define PN_VIEWER_SOURCE_3D 2

#define PN_VIEWER_CHANNEL_RGB 4    // channels 0..3 = r, g, b, a; 4 = rgb together

// A debug image's "no data" value (DebugImage::noData) is drawn in slate: neither a grey nor a
// Turbo colour. The legend shows the same swatch.
#define PN_VIEWER_NO_DATA_RGB 0.16f, 0.2f, 0.32f

#define PN_VIEWER_MAP_GREY 0
#define PN_VIEWER_MAP_TURBO 1      // Google's Turbo rainbow: small differences stand out

#define PN_VIEWER_GROUP 8          // workgroup side of the range pass

PN_GPU_BEGIN

struct ViewerDisplayUniforms {
  ivec4 source;  // x: layer (array) or slice (3D), y: mip level, z: channel (0..3 or PN_VIEWER_CHANNEL_RGB), w: PN_VIEWER_MAP_*
  ivec4 rect;    // xy: lower-left corner in window pixels, zw: size in pixels
  ivec4 mode;    // x: 1 = range measured into the range buffer, 0 = fixed range; y: 1 = range.z is "no data"; zw: unused
  vec4 range;    // x: fixed minimum, y: fixed maximum (values mapped to 0 and 1); z: the no-data value; w: unused
};

PN_GPU_END

#ifdef __cplusplus
static_assert(sizeof(penumbra::gpu::ViewerDisplayUniforms) == 64, "std140 size of ViewerDisplayUniforms");
#endif
