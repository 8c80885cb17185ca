#pragma once
// One invocation per pixel of a full-screen pass, in either stage (frame/ScreenTarget.h):
//  - compute (the default): one thread per pixel in groups of PN_SCREEN_GROUP², the result
//    stored into the pass's image;
//  - with PN_SCREEN_FRAGMENT: the fragment shader of a full-screen triangle, the result written
//    to colour attachment 0 (the image is then not declared).
// screenPixel(px, size) gives the pixel and whether it lies inside size (a group's threads past
// the screen's edge do nothing); screenStore(image, px, value) writes the pass's result.
#include "shared/Bindings.h"

#ifdef PN_SCREEN_FRAGMENT
layout(location = 0) out vec4 o_screen;
bool screenPixel(out ivec2 px, ivec2 size) {
  px = ivec2(gl_FragCoord.xy);  // the pixel's centre is at +0.5: its integer part is the pixel
  return true;                  // the viewport is the screen
}
#define screenStore(image, px, value) (o_screen = (value))
#else
layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
bool screenPixel(out ivec2 px, ivec2 size) {
  px = ivec2(gl_GlobalInvocationID.xy);
  return all(lessThan(px, size));
}
#define screenStore(image, px, value) imageStore(image, px, value)
#endif
