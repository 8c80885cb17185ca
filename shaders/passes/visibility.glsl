// The visibility pass: one invocation per pixel; V = shadowVisibility(...) of the active filter
// for pixels that face the light, 0 for pixels that face away (no direct light reaches them),
// 1 where there is no geometry. Inside a cascade blend band V mixes two cascades (the filter is
// run once per cascade with selectShadowView forced). Over the screen it is the fragment shader
// of a full-screen triangle drawn into the light's visibility layer (frame/ScreenTarget.h). With
// PN_VISIBILITY_POINTS defined the same is done, as a compute shader, for a list of world points
// (visibilityAt) instead of the surfaces. With PN_SURFACE_FROM_DEPTH the surface positions come
// from the camera's depth texture; with PN_NORMALS_FROM_POSITIONS their normals from their
// neighbours (common/visibility.glsl).
// A pass whose file defines PN_SHADOW_VALUE as vec3 (the translucent add-on's tint) computes
// a colour per pixel, written as (r, g, b, 1); a filter's one value v is written as (v, v, v, v).
#include "common/visibility.glsl"
#include "shared/VisibilityPoints.h"

#ifndef PN_SHADOW_VALUE
#define PN_SHADOW_VALUE float
#endif
vec4 shadowOutput(float v) { return vec4(v); }
vec4 shadowOutput(vec3 v) { return vec4(v, 1.0); }

PN_SHADOW_VALUE blendedVisibility(SurfacePoint s) {
#ifdef PN_VIRTUAL_PAGES
  // A clipmap's level by the pixel's footprint on its surface, as the page marking chose it.
  ShadowViewBlend b = ShadowViewBlend(virtualLevelFor(s.ws, s.geoNormal), 0, 0.0);
  b.second = b.first;
#else
  ShadowViewBlend b = shadowViewBlend(s.ws);
#endif
  g_forcedShadowView = b.first;
  PN_SHADOW_VALUE v = clamp(shadowVisibility(s), 0.0, 1.0);
  if (b.weight > 0.0) {
    g_forcedShadowView = b.second;
    v = mix(v, clamp(shadowVisibility(s), 0.0, 1.0), b.weight);
  }
  g_forcedShadowView = -1;
  return v;
}

PN_SHADOW_VALUE surfaceVisibility(vec3 ws, vec3 geoNormal, ivec2 px) {
  SurfacePoint s;
  s.ws = ws;
  s.geoNormal = normalize(geoNormal);
  s.toLight = toLight(s.ws);
  s.NoL = dot(s.geoNormal, s.toLight);
  s.pixel = px;
  return s.NoL > 0.0 ? blendedVisibility(s) : PN_SHADOW_VALUE(0.0);
}

#ifdef PN_VISIBILITY_POINTS

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std430, binding = PN_SSBO_POINTS) readonly buffer PointBlock {
  ivec4 u_pointInfo;  // x: count, y: grid width
  VisibilityPointGpu u_points[];
};
layout(std430, binding = PN_SSBO_POINT_VISIBILITY) writeonly buffer PointVisibilityBlock { float o_pointVisibility[]; };

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  int i = id.y * u_pointInfo.y + id.x;
  if (id.x >= u_pointInfo.y || i >= u_pointInfo.x) return;
  VisibilityPointGpu p = u_points[i];
  o_pointVisibility[i] = surfaceVisibility(p.position.xyz, p.geoNormal.xyz, p.pixel.xy);
}

#else

layout(location = 0) out vec4 o_visibility;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);  // the pixel's centre is at +0.5: its integer part is the pixel
  vec4 pos = surfacePosition(px);
  PN_SHADOW_VALUE v = PN_SHADOW_VALUE(1.0);
  if (pos.w > 0.5) v = surfaceVisibility(pos.xyz, surfaceGeoNormal(px, pos.xyz), px);
  o_visibility = shadowOutput(v);
}

#endif
