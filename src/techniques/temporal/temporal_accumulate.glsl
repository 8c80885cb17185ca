// Temporal accumulation (docs/temporal.md): this frame's V, in the light's layer of the
// visibility image, blended with the V accumulated over earlier frames. Each pixel's surface is
// reprojected into the previous frame's camera; the four history texels around it (bilinear)
// count only where the previous frame saw a surface on this pixel's tangent plane (within
// temporal.tolerancePx pixel footprints) facing the same way (normals within kMaxTurnCos), so
// disoccluded and moved surfaces start afresh: a floor pixel that saw the bottom of a ball the
// frame before lies near the floor's plane, but faces elsewhere. The
// history is then held to this frame's 3×3 neighbourhood of V (its min/max, or mean ± γσ) and
// blended: V = mix(history, V_now, α), α rising to 1 where V_now and the history differ by more
// than temporal.snapV (beside an edge the neighbourhood's range is all of [0, 1]). The result goes to the light's other
// history image; the core copies it into the visibility layer. Surfaces that move (no motion vectors here) are
// found again only within the tolerance; the neighbourhood clamp bounds the lag elsewhere.
#include "common/visibility.glsl"
#include "techniques/temporal/temporal.shared.h"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std140, binding = PN_UBO_FILTER) uniform TemporalBlock { TemporalUniforms u_temporal; };
layout(binding = PN_IMG_VISIBILITY, PN_VISIBILITY_FORMAT) uniform readonly image2D i_visibility;  // this frame's V
layout(binding = PN_IMG_OUTPUT, PN_VISIBILITY_FORMAT) uniform writeonly image2D i_accumulated;
layout(binding = PN_TEX_HISTORY) uniform sampler2D s_history;  // this light's V of the frames before
layout(binding = PN_TEX_PREVIOUS_SURFACE) uniform sampler2D s_previousSurface;
layout(binding = PN_TEX_PREVIOUS_NORMAL) uniform sampler2D s_previousNormal;

// The least cosine between this frame's normal and the previous frame's for the same surface: a
// surface turns by a few degrees a frame at most; another surface meeting it (a caster on its
// receiver) mostly faces elsewhere.
const float kMinNormalCos = 0.9;  // 26 degrees

// The history at ws (bilinear over the texels whose previous surface lies on ws's tangent
// plane); false when none does or ws was off the previous screen.
bool reprojectedHistory(vec3 ws, vec3 n, out VisibilityValue history) {
  vec4 clip = u_temporal.previousClipFromWorld * vec4(ws, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 at = (clip.xy / clip.w * 0.5 + 0.5) * vec2(u_frame.screen.xy) - 0.5;  // texel-centre coordinates
  ivec2 base = ivec2(floor(at));
  vec2 f = at - vec2(base);
  float toleranceM = u_temporal.blend.y * u_temporal.blend.z * pixelScaleAt(ws);
  VisibilityValue sum = VisibilityValue(0.0);
  float weightSum = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = base + ivec2(i & 1, i >> 1);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_frame.screen.xy))) continue;
    vec4 previous = texelFetch(s_previousSurface, q, 0);
    if (previous.w < 0.5 || abs(dot(previous.xyz - ws, n)) > toleranceM ||
        dot(texelFetch(s_previousNormal, q, 0).xyz, n) < kMinNormalCos)
      continue;
    float w = ((i & 1) == 1 ? f.x : 1.0 - f.x) * ((i >> 1) == 1 ? f.y : 1.0 - f.y);
    sum += w * visibilityOfTexel(texelFetch(s_history, q, 0));
    weightSum += w;
  }
  const float kMinWeight = 1e-3;  // below it the surviving texels are too far off to interpolate from
  if (weightSum < kMinWeight) return false;
  history = sum / weightSum;
  return true;
}

// The history held to the range of this frame's V around px (per channel).
VisibilityValue clampToNeighbourhood(VisibilityValue history, ivec2 px) {
  int mode = int(u_temporal.clip.x);
  if (mode == PN_TEMPORAL_CLAMP_OFF) return history;
  VisibilityValue lo = VisibilityValue(1.0), hi = VisibilityValue(0.0), sum = VisibilityValue(0.0), sumSq = VisibilityValue(0.0);
  float count = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(px + ivec2(dx, dy), ivec2(0), u_frame.screen.xy - 1);
      VisibilityValue v = visibilityOfTexel(imageLoad(i_visibility, q));
      lo = min(lo, v);
      hi = max(hi, v);
      sum += v;
      sumSq += v * v;
      count += 1.0;
    }
  }
  if (mode == PN_TEMPORAL_CLAMP_VARIANCE) {
    VisibilityValue mean = sum / count;
    VisibilityValue sigma = sqrt(max(sumSq / count - mean * mean, VisibilityValue(0.0)));
    lo = max(lo, mean - u_temporal.clip.y * sigma);
    hi = min(hi, mean + u_temporal.clip.y * sigma);
  }
  return clamp(history, lo, hi);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  VisibilityValue v = visibilityOfTexel(imageLoad(i_visibility, px));
  vec4 pos = surfacePosition(px);
  VisibilityValue history;
  if (pos.w > 0.5 && u_temporal.blend.w > 0.5 &&
      reprojectedHistory(pos.xyz, normalize(surfaceGeoNormal(px, pos.xyz)), history))
  {
    history = clampToNeighbourhood(history, px);
    // A change far beyond the filter's noise (a shadow arriving or leaving whole) is taken at
    // once, over a short ramp past the threshold: beside an edge the clamp's range is all of [0, 1].
    const float kSnapRampV = 0.25;
    float snap = u_temporal.clip.z;
    VisibilityValue weight = mix(VisibilityValue(u_temporal.blend.x), VisibilityValue(1.0),
                                 smoothstep(snap, snap + kSnapRampV, abs(v - history)));
    v = mix(history, v, weight);
  }
  imageStore(i_accumulated, px, visibilityTexel(v));
}
