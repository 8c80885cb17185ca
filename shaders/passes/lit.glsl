// Lit pass, identical for every technique: ambient + Σ over the lights of V_i · direct_i (Lambert
// + Blinn-Phong), an ACES-style tone map and sRGB encoding. The subject of Penumbra is V, so
// shading stays simple. V_i is layer i of the visibility array. The fragment shader of a
// full-screen triangle drawn into the colour target (frame/ScreenTarget.h).
#include "common/frame.glsl"
#include "common/texel_density.glsl"
#include "shared/DebugColors.h"
#include "shared/DensityRamp.h"

layout(binding = PN_TEX_GBUF_POSITION) uniform sampler2D s_gbufPosition;
layout(binding = PN_TEX_GBUF_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = PN_TEX_GBUF_ALBEDO) uniform sampler2D s_gbufAlbedo;
layout(binding = PN_TEX_VISIBILITY) uniform sampler2DArray s_visibility;
// PN_LIT_LIGHTS (a define): the frame's light count; PN_ONLY_SUNS (defined or not): no spot or
// point light among them (common/frame.glsl).
layout(std430, binding = PN_SSBO_LIGHTS) readonly buffer LightsBlock { LightGpu u_lights[]; };
layout(location = 0) out vec4 o_color;
// PN_VISIBILITY_RGB (defined or not): the visibility array holds RGB (translucent casters tint
// V; penumbra/Shadows.h visibilityHasColour), which multiplies each light's colour channel by channel.
#ifdef PN_VISIBILITY_RGB
#define LitVisibility vec3
#define litVisibility(texel) (texel).rgb
#else
#define LitVisibility float
#define litVisibility(texel) (texel).r
#endif
// PN_DEBUG_VIEW (a define, PN_VIEW_*): what the pass writes.
const int kDebugView = PN_DEBUG_VIEW;

const float kSpecularStrength = 0.25;  // share of the direct light reflected specularly

vec3 acesApprox(vec3 x) {  // Narkowicz's fit of the ACES filmic curve
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec3 toSrgb(vec3 c) {
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// The debug views that tint the shaded image: the shading stays visible under the tint.
vec3 debugTint(ivec2 px, vec3 ws, vec3 shaded) {
  const float kBaseShade = 0.35;  // darkest a shadowed surface gets under the tint
  float shade = kBaseShade + (1.0 - kBaseShade) * dot(shaded, vec3(0.2126, 0.7152, 0.0722));
  if (kDebugView == PN_VIEW_CASCADES) {
    ShadowViewBlend b = shadowViewBlend(ws);
#ifdef PN_VIRTUAL_PAGES
    // A paged light's level (a point light's views are its six faces' levels, face after face).
    return shade * cascadeColor(b.first % virtualLevels()).rgb;
#else
    return shade * mix(cascadeColor(b.first).rgb, cascadeColor(b.second).rgb, b.weight);
#endif
  }
  float density = screenPixelsPerTexel(s_gbufPosition, px);
  return density > 0.0 ? shade * densityRampColor(log2(density)).rgb : vec3(shade);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(s_gbufPosition, px, 0);
  vec3 color;
  if (pos.w < 0.5) {
    float t = float(px.y) / float(u_frame.screen.y);
    color = mix(vec3(0.55, 0.6, 0.65), vec3(0.25, 0.4, 0.65), t);  // sky gradient (display-referred)
  } else {
    vec3 n = texelFetch(s_gbufNormal, px, 0).xyz;
    vec3 albedo = texelFetch(s_gbufAlbedo, px, 0).rgb;
    vec3 toCamera = normalize(u_frame.cameraPosition.xyz - pos.xyz);
    vec3 hdr = u_frame.ambient.rgb * albedo;
    // The visibility view: each light's V weighted by its unshadowed light here (what the
    // metrics call the combined V; a single light's own V).
    LitVisibility weightedV = LitVisibility(0.0);
    float weights = 0.0;
    for (int i = 0; i < PN_LIT_LIGHTS; ++i) {
      LightGpu light = u_lights[i];
      LitVisibility v = litVisibility(texelFetch(s_visibility, ivec3(px, i), 0));
      vec3 l = toLightOf(light, pos.xyz);
      vec3 radiance = light.radiance.rgb;
      if (isPositional(light)) {
        vec3 d = light.position.xyz - pos.xyz;
        radiance *= lightFalloffOf(light, pos.xyz) / max(dot(d, d), 1e-4);
      }
      vec3 h = normalize(l + toCamera);
      float NoL = max(dot(n, l), 0.0);
      float specular = kSpecularStrength * pow(max(dot(n, h), 0.0), 48.0) * step(0.0, NoL);
      hdr += v * (albedo * NoL + specular) * radiance;
      float w = NoL * dot(radiance, vec3(0.2126, 0.7152, 0.0722));
      weightedV += w * v;
      weights += w;
    }
    color = kDebugView == PN_VIEW_VISIBILITY ? vec3(weights > 0.0 ? weightedV / weights : litVisibility(texelFetch(s_visibility, ivec3(px, 0), 0)))
                                             : toSrgb(acesApprox(hdr));
  }
  if (pos.w > 0.5 && (kDebugView == PN_VIEW_CASCADES || kDebugView == PN_VIEW_TEXEL_DENSITY))
    color = debugTint(px, pos.xyz, color);
  o_color = vec4(color, 1.0);
}
