// Contact shadows: from each pixel's surface, PN_CONTACT_STEPS samples along the ray toward the
// light's centre over contact.distanceM; a sample that lies behind the depth buffer (farther from
// the camera than the surface drawn at its pixel) by more than the tolerance and less than
// contact.thicknessM is inside a caster, and the pixel is in its shadow: V = min(V, t / distance)
// for the first such sample t metres along (dark at the contact, fading toward the end). A sample
// that leaves the screen or passes behind the camera ends the march unoccluded (the depth buffer
// knows nothing there). Assumptions, and so its own errors: every surface in the depth buffer
// is contact.thicknessM thick (thin casters seen edge-on, or walls seen from the front, shadow
// what lies within that depth behind them), and casters the camera does not see cast nothing.
// One ray toward the light's centre: its fade stands in for a penumbra, growing with the
// occluder's distance.
#include "common/sampling.glsl"
#include "common/visibility.glsl"
#include "techniques/contact/contact.shared.h"

layout(local_size_x = PN_SCREEN_GROUP, local_size_y = PN_SCREEN_GROUP) in;
layout(std140, binding = PN_UBO_FILTER) uniform ContactBlock { ContactUniforms u_contact; };
layout(binding = PN_IMG_VISIBILITY, PN_VISIBILITY_FORMAT) uniform image2D i_visibility;

// How far (m) p lies behind the surface drawn at pixel q, along the camera ray through p: the
// ray is met with q's surface plane (its position and normal), not with q's centre depth, so the
// depth buffer's steps across a tilted or distant surface do not read as casters. Negative: in
// front. A plane seen edge-on falls back to the centre's distance.
float behindSurface(vec3 p, ivec2 q) {
  vec4 surface = surfacePosition(q);
  if (surface.w < 0.5) return -1.0;  // background: nothing there
  vec3 eye = cameraEyeFor(p);
  vec3 d = p - eye;
  float sampleM = length(d);
  d /= sampleM;
  vec3 n = surfaceGeoNormal(q, surface.xyz);
  float dn = dot(d, n);
  const float kEdgeOn = 1e-3;  // |cos| below which the plane gives no usable intersection
  float surfaceM = abs(dn) > kEdgeOn ? dot(surface.xyz - eye, n) / dn : distance(surface.xyz, eye);
  return sampleM - surfaceM;
}

// The march from ws toward the light: the distance (m) along it of the first sample inside a
// surface of the depth buffer, or -1 when there is none.
float contactHitM(vec3 ws, vec3 n, ivec2 px) {
  vec3 l = toLight(ws);
  vec3 start = ws + n * u_contact.march.z;
  float stepM = u_contact.march.x / float(PN_CONTACT_STEPS);
  // Per-pixel jitter of the first step: a fixed lattice would band along the caster.
  float jitter = pixelNoise(px, samplingFrame());
  for (int i = 0; i < PN_CONTACT_STEPS; ++i) {
    float t = (float(i) + jitter) * stepM;
    vec3 p = start + l * t;
    vec4 clip = u_frame.clipFromWorld * vec4(p, 1.0);
    if (clip.w <= 0.0) return -1.0;
    vec2 ndc = clip.xy / clip.w;
    if (any(greaterThan(abs(ndc), vec2(1.0)))) return -1.0;
    ivec2 q = clamp(ivec2((ndc * 0.5 + 0.5) * vec2(u_frame.screen.xy)), ivec2(0), u_frame.screen.xy - 1);
    if (q == px) continue;  // the receiver's own pixel
    float behind = behindSurface(p, q);
    if (behind > u_contact.march.w * pixelScaleAt(p) && behind < u_contact.march.y) return t;
  }
  return -1.0;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, u_frame.screen.xy))) return;
  VisibilityValue v = visibilityOfTexel(imageLoad(i_visibility, px));
  if (all(lessThanEqual(vec3(v), vec3(0.0)))) return;  // already dark (or facing away): nothing to add
  vec4 pos = surfacePosition(px);
  if (pos.w < 0.5) return;
  vec3 n = normalize(surfaceGeoNormal(px, pos.xyz));
  float hitM = contactHitM(pos.xyz, n, px);
  // Dark at the contact, fading out toward the march's end: an occluder farther along the ray
  // casts a wider penumbra (and is the shadow map's to resolve), so a hard V = 0 there would
  // paint a dark band over soft shadows.
  const float kFadeStart = 0.5;  // share of the march over which the contact stays fully dark
  if (hitM >= 0.0)
    imageStore(i_visibility, px, visibilityTexel(min(v, VisibilityValue(smoothstep(kFadeStart, 1.0, hitM / u_contact.march.x)))));
}
