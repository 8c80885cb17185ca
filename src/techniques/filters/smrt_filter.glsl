// smrt's spatial filter: the rays' noise (a few rays a pixel, turned per pixel) averaged along the
// shadow's edge. A penumbra changes across its edge and hardly along it, and is often only a few
// pixels wide, so a blur across it would widen it: each pixel whose rays disagree (0 < V < 1)
// takes the tent-weighted mean of V over smrt.filterRadiusPx pixels on either side along the
// edge, the direction across which V does not change (normal to V's gradient, a Sobel operator
// over the 3×3 neighbourhood). A neighbour counts where its surface lies on the pixel's tangent
// plane (within kMaxPlaneTangent of it, seen from the pixel) and faces the same way, so a shadow
// does not bleed across a caster's outline onto its receiver. Pass 0 writes the means into a
// scratch image, pass 1 copies them into the visibility layer; a pixel every ray agreed on
// (V = 0 or 1) stays as it is.
#include "common/visibility.glsl"
#include "techniques/filters/smrt.shared.h"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std140, binding = PN_UBO_FILTER) uniform SmrtBlock { SmrtUniforms u_smrt; };
layout(binding = PN_IMG_VISIBILITY, r32f) uniform image2D i_visibility;
layout(binding = PN_IMG_AUX0, r32f) uniform image2D i_means;  // pass 0's means
layout(location = PN_LOC_SWITCH) uniform int u_copy;           // 0: average into i_means, 1: copy them back

// A neighbour on the pixel's own surface lies within this tangent of its plane (6 degrees: a
// curved caster's neighbouring pixels, not the receiver beyond its outline) …
const float kMaxPlaneTangent = 0.1;
// … and its normal within this cosine of the pixel's (26 degrees).
const float kMinNormalCos = 0.9;

float visibilityAt(ivec2 q) { return imageLoad(i_visibility, clamp(q, ivec2(0), u_frame.screen.xy - 1)).r; }

// V's gradient at px (per pixel), by a Sobel operator over its 3×3 neighbourhood.
vec2 visibilityGradient(ivec2 px) {
  float v00 = visibilityAt(px + ivec2(-1, -1)), v10 = visibilityAt(px + ivec2(0, -1)), v20 = visibilityAt(px + ivec2(1, -1));
  float v01 = visibilityAt(px + ivec2(-1, 0)), v21 = visibilityAt(px + ivec2(1, 0));
  float v02 = visibilityAt(px + ivec2(-1, 1)), v12 = visibilityAt(px + ivec2(0, 1)), v22 = visibilityAt(px + ivec2(1, 1));
  return vec2(v20 + 2.0 * v21 + v22 - v00 - 2.0 * v01 - v02, v02 + 2.0 * v12 + v22 - v00 - 2.0 * v10 - v20) / 8.0;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  float v = imageLoad(i_visibility, px).r;
  if (v <= 0.0 || v >= 1.0) return;  // every ray agreed (or background, or facing away): kept
  if (u_copy != 0) {
    imageStore(i_visibility, px, imageLoad(i_means, px));
    return;
  }
  vec4 pos = surfacePosition(px);
  vec3 n = normalize(texelFetch(s_gbufGeoNormal, px, 0).xyz);
  vec2 gradient = visibilityGradient(px);
  float slope = length(gradient);
  vec2 along = slope > 0.0 ? vec2(-gradient.y, gradient.x) / slope : vec2(1.0, 0.0);
  int radius = int(u_smrt.spatial.x);
  float sum = v, weightSum = 1.0;
  for (int d = -radius; d <= radius; ++d) {
    if (d == 0) continue;
    // The tap, between pixel centres: the four around it, bilinear, each where it lies on px's surface.
    vec2 at = vec2(px) + float(d) * along;
    ivec2 base = ivec2(floor(at));
    vec2 f = at - vec2(base);
    float tent = 1.0 - float(abs(d)) / float(radius + 1);
    for (int k = 0; k < 4; ++k) {
      ivec2 q = base + ivec2(k & 1, k >> 1);
      float w = tent * ((k & 1) == 1 ? f.x : 1.0 - f.x) * ((k >> 1) == 1 ? f.y : 1.0 - f.y);
      if (w <= 0.0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_frame.screen.xy))) continue;
      vec4 other = surfacePosition(q);
      vec3 offset = other.xyz - pos.xyz;
      if (q != px && (other.w < 0.5 || abs(dot(offset, n)) > kMaxPlaneTangent * length(offset) ||
                      dot(normalize(texelFetch(s_gbufGeoNormal, q, 0).xyz), n) < kMinNormalCos))
        continue;
      sum += w * imageLoad(i_visibility, q).r;
      weightSum += w;
    }
  }
  imageStore(i_means, px, vec4(sum / weightSum));
}
