#pragma once
// Flicker: the share of surface points, followed in world space from one frame to the next, whose
// V changes by more than 0.1 while V_ref changes by less than 0.02 — change that the technique
// makes and the light does not (crawling shadow-map texels, a filter's noise). A point is the
// surface seen at a pixel of frame k; it is followed on its object (its object-space position
// carried by the object's transform of frame k+1, so a moving caster's points move with it),
// projected into frame k+1 and kept when the pixel there sees the same object within a few
// pixels' footprint of it (not hidden, not off screen). The technique's V of frame k+1 is taken
// at the followed point itself (Renderer::visibilityAt), not at the pixel it lands on: a jagged
// edge under a sub-pixel re-projection is not flicker (a V tinted by translucent casters, which
// visibilityAt does not give, is read at that pixel: compareSequence). V_ref is compared pixel to
// pixel (a reference that changes there only excludes the point). No GL here: the frames are read-backs.
#include <penumbra/Image.h>
#include <penumbra/Math.h>
#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace penumbra {

struct FlickerOptions {
  float changeThresholdV = 0.1f;     ///< the technique's V "changes" beyond this
  float referenceStillV = 0.02f;     ///< while V_ref changes less than this
  /// A followed point is found in the next frame when the pixel it lands on is within this many
  /// pixel footprints (at its distance from the camera) of it.
  float followTolerancePx = 2.0f;
};

/// One frame of one light as flicker needs it (arrays width × height, row 0 = bottom as GL reads back).
struct FlickerFrame {
  int width = 0, height = 0;
  glm::mat4 clipFromWorld{1.0f};
  glm::vec3 cameraPosition{0.0f};
  float pixelAngleRad = 0.0f;  ///< 2·tan(fovY/2)/height: a pixel's footprint per metre of distance
  std::vector<glm::vec3> position, geoNormal;  ///< world position and geometric normal per pixel
  std::vector<uint32_t> object;                ///< Scene::objects index + 1; 0 = background
  std::vector<float> v, vRef;                  ///< the technique's V and the reference's
  std::vector<uint8_t> mask;                   ///< 1 where V_ref is defined (the light's litMask)
  std::vector<glm::mat4> worldFromObject;      ///< every object's transform in this frame
};

/// Builds a frame from the renderer's read-backs of one light.
FlickerFrame makeFlickerFrame(const GBufferData& gbuffer, const Camera& camera, std::vector<float> v, std::vector<float> vRef,
                              std::vector<uint8_t> mask, std::vector<glm::mat4> worldFromObject);

/// A point of frame `from` (pixel index `from`) found in frame `to` at pixel index `to`; `at` is
/// the point itself in frame `to` (position and normal on its moved object, the pixel it lands on).
struct FollowedPoint {
  size_t from = 0, to = 0;
  SurfaceSample at;
};

/// The points of `from` followed into `to` (consecutive frames of one scene); `to`'s v is not read.
std::vector<FollowedPoint> followPoints(const FlickerFrame& from, const FlickerFrame& to, const FlickerOptions& options = {});

struct FlickerCounts {
  size_t followed = 0;    ///< (point, frame pair) found in both frames
  size_t flickering = 0;  ///< of those, V changed and V_ref did not
  FlickerCounts& operator+=(const FlickerCounts& o) {
    followed += o.followed;
    flickering += o.flickering;
    return *this;
  }
  /// flicker_pct: 100 · flickering / followed (0 when nothing was followed).
  double pct() const { return followed ? 100.0 * static_cast<double>(flickering) / static_cast<double>(followed) : 0.0; }
};

/// Counts the followed points whose V changed (`from.v` at the pixel against `vAt`, the
/// technique's V of frame `to` at each point) while V_ref did not. Throws penumbra::Error when
/// the counts differ.
FlickerCounts countFlicker(const FlickerFrame& from, const FlickerFrame& to, std::span<const FollowedPoint> points,
                           std::span<const float> vAt, const FlickerOptions& options = {});

}  // namespace penumbra
