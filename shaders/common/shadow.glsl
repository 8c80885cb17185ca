#pragma once
// Shadow-map addressing shared by every filter: which view (cascade) covers a point, where the
// point falls in that view's map, its linear light depth, and the world size of one texel there.
#include "common/frame.glsl"

int shadowViewCount() { return u_shadow.info.x; }
float shadowMapSize() { return float(u_shadow.info.y); }

// Linear light-space depth in [0,1] (DESIGN.md: shadow maps store linear depth).
float lightDepth(int view, vec3 ws) { return dot(u_shadow.views[view].depthPlane, vec4(ws, 1.0)); }

// Distance (m) from the light along its axis.
float lightDistance(int view, vec3 ws) {
  vec4 r = u_shadow.views[view].range;
  return r.x + lightDepth(view, ws) * (r.y - r.x);
}

bool isPerspectiveView(int view) { return u_shadow.views[view].range.z > 0.5; }

// xy: map uv in [0,1]; z: linear depth in [0,1].
vec3 shadowCoord(int view, vec3 ws) {
  vec4 c = u_shadow.views[view].clipFromWorld * vec4(ws, 1.0);
  return vec3(c.xy / c.w * 0.5 + 0.5, lightDepth(view, ws));
}

// World-space size (m) of one shadow-map texel at ws (the larger side of a non-square texel).
float shadowTexelWorldSize(int view, vec3 ws) {
  float extent = max(u_shadow.views[view].extent.x, u_shadow.views[view].extent.y);
  float scale = isPerspectiveView(view) ? lightDistance(view, ws) : 1.0;
  return extent * scale / shadowMapSize();
}

// Metres of light-axis distance per unit of stored depth.
float depthRangeM(int view) { return u_shadow.views[view].range.y - u_shadow.views[view].range.x; }

// The view (cascade) whose split contains this point's camera depth; the last one otherwise.
int selectShadowView(vec3 ws) {
  float viewDepth = -(u_frame.viewFromWorld * vec4(ws, 1.0)).z;
  int n = shadowViewCount();
  for (int i = 0; i < n - 1; ++i)
    if (viewDepth <= u_shadow.views[i].range.w) return i;
  return n - 1;
}

bool insideMap(vec3 coord) { return all(greaterThanEqual(coord.xy, vec2(0.0))) && all(lessThanEqual(coord.xy, vec2(1.0))); }
