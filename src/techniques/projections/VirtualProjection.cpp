#include "techniques/projections/VirtualProjection.h"

#include "techniques/projections/LightSpace.h"
#include "shared/Bindings.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace penumbra {
namespace {

// A sun's clipmap levels at most (each level is one shadow view); a point light's six faces take
// at most a sixth of the views each.
constexpr int kMaxLevels = 16;
static_assert(kMaxLevels <= PN_MAX_SHADOW_VIEWS);

constexpr ParamDesc kParams[] = {
    {"virtual.levels", "Levels", "a sun's clipmap levels around the camera, each a virtual map twice as wide as the one before; a "
     "spot's mips of its one view and each of a point light's six faces' mips, each half the last's resolution (at most "
     "log2(virtual size / page size) + 1, and 8 a face; a pixel reads those at least 1024 texels across)", "levels",
     12.0f, 1.0f, static_cast<float>(kMaxLevels), 1.0f},
    {"virtual.firstLevelM", "First level", "width of a sun's finest level's square in metres (its texel: this / virtual size); a "
     "spot's finest level is its whole view", "m",
     16.0f, 0.25f, 4096.0f, 0.0f},
    {"virtual.virtualSize", "Virtual size", "texels per side of each level's virtual map (a power of two, a multiple of the page size)",
     "texels", 16384.0f, 1024.0f, 16384.0f, 1.0f},
    {"virtual.pageSize", "Page size", "texels per side of a page, the unit that is marked, drawn and cached (a power of two)", "texels",
     128.0f, 32.0f, 512.0f, 1.0f},
    {"virtual.poolPages", "Pool", "pages the pool holds: its fixed memory is this × page size² × 4 bytes (× 2 with cached map "
     "updates, which keep the static casters' copy); when a frame needs more, coarser levels serve the rest", "pages",
     2048.0f, 16.0f, 16384.0f, 1.0f},
    {"virtual.marginTexels", "Margin", "texels around each pixel's texel whose pages are marked with it (a filter's kernel reads "
     "there; beyond, a coarser level serves)", "texels", 4.0f, 0.0f, 64.0f, 1.0f},
    {"virtual.levelBias", "Level bias", "levels added to each pixel's choice: + reads coarser levels (fewer pages, one texel over "
     "several pixels), − finer ones", "levels", 0.0f, -2.0f, 4.0f, 0.0f},
    {"virtual.cubeGuardTexels", "Cube guard band",
     "point lights: each cube face's virtual map reaches this many of its finest level's texels past the face's edge (a "
     "coarser level's band is as wide in the scene, fewer of its texels), so a kernel, blocker search or ray near the edge "
     "reads the scene beyond it instead of clamping",
     "texels", 256.0f, 0.0f, 4096.0f, 1.0f, {}, {}, kPointLightBit},
    {"virtual.grazingLevels", "Grazing levels", "where the camera grazes a surface more than the light does, each doubling of "
     "that ratio reads a level finer, up to this many (thin shadows far off resolved across their width)", "levels", 1.0f, 0.0f,
     3.0f, 0.0f},
};

// The depth range is the scene's along the light, widened to whole steps of an eighth of its
// power-of-two span: a caster that moves a little inside the scene leaves it (and every page's
// stored depths) as it was.
constexpr float kDepthStepsPerSpan = 8.0f;

}  // namespace

VirtualProjection::VirtualProjection() : Projection(kParams) {}

// Perspective views in mips (a spot's one view, each of a point light's faces): level l holds the
// view at virtualSize / 2^l texels, its clip square mapping the view onto the corner [0, 2^-l]² of
// the level's virtual square (uv_l = 2^-l · uv_0), so every level keeps the page table's and the
// filters' addressing (virtualSize texels a side, pages on one grid) and a level uses its first
// (pagesPerSide / 2^l)² pages. Levels stop where the view fits one page (a read past the resident
// pages always finds that one); a point light's faces take `levels` views each, face after face
// (view = face · levels + level).
int VirtualProjection::mipLevels(const Light& light, const PageLayout& layout) const {
  const int fit = std::countr_zero(static_cast<unsigned>(layout.pagesPerSide())) + 1;
  const int most = light.type == LightType::Point ? PN_MAX_SHADOW_VIEWS / kCubeFaces : kMaxLevels;
  return std::min({paramInt("virtual.levels"), fit, most});
}

void VirtualProjection::appendMips(const ShadowView& base, int levels, LightFrusta& f) {
  for (int level = 0; level < levels; ++level) {
    const float s = std::exp2(-static_cast<float>(level));
    // clip'.xy = s·clip.xy + (s − 1)·clip.w: ndc' = s·(ndc + 1) − 1.
    glm::mat4 corner(1.0f);
    corner[0][0] = corner[1][1] = s;
    corner[3][0] = corner[3][1] = s - 1.0f;
    ShadowView v = base;
    v.clipFromWorld = corner * base.clipFromWorld;
    v.extent = base.extent / s;  // the level's whole virtual square, at 1 m from the light
    f.views.push_back(v);
  }
}

// A spot light: one perspective view of the whole scene from the light (clamped to its cone),
// fitted to the scene's bounds alone so that it stays while the camera moves, in mips. A point
// light: its six cube faces, each in mips, fixed as the spot's.
LightFrusta VirtualProjection::perspectiveMips(const Light& light, const SceneExtent& scene, const PageLayout& layout) const {
  const int levels = mipLevels(light, layout);
  LightFrusta f;
  if (light.type == LightType::Point) {
    for (const ShadowView& face : cubeFaceViews(light, scene, layout.virtualSize, param("virtual.cubeGuardTexels")).views)
      appendMips(face, levels, f);
    return f;
  }
  Aabb bounds = scene.bounds();
  if (bounds.empty()) bounds = Aabb{light.position - glm::vec3(1.0f), light.position + glm::vec3(1.0f)};
  const std::array<glm::vec3, 8> corners = bounds.corners();
  appendMips(fitLightView(scene, light, corners, corners, 0.0f), levels, f);
  return f;
}

std::string VirtualProjection::incompatibility(const Light& light) const {
  (void)light;  // every kind of light is paged
  const int size = paramInt("virtual.virtualSize"), page = paramInt("virtual.pageSize");
  if (!std::has_single_bit(static_cast<unsigned>(size)) || !std::has_single_bit(static_cast<unsigned>(page)))
    return fmt::format("virtual.virtualSize {} and virtual.pageSize {} must be powers of two", size, page);
  if (page > size) return fmt::format("virtual.pageSize {} is larger than virtual.virtualSize {}", page, size);
  return {};
}

std::optional<PageLayout> VirtualProjection::pageLayout() const {
  PageLayout l;
  l.virtualSize = paramInt("virtual.virtualSize");
  l.pageSize = paramInt("virtual.pageSize");
  l.poolPages = paramInt("virtual.poolPages");
  l.marginTexels = param("virtual.marginTexels");
  l.levelBias = param("virtual.levelBias");
  l.grazingLevels = param("virtual.grazingLevels");
  return l;
}

LightFrusta VirtualProjection::computeFrusta(const Camera& camera, float aspect, const Light& light, const SceneExtent& scene,
                                             int mapSize) const {
  (void)aspect;
  (void)mapSize;
  const PageLayout layout = *pageLayout();
  if (light.type != LightType::Directional) return perspectiveMips(light, scene, layout);
  // The light's rotation alone (the eye at the world's origin): every level shares it, and a
  // level's place is its translation (common/shadow.glsl: virtualUvInLevel).
  const glm::mat4 lightFromWorld = lightViewMatrix(glm::vec3(0.0f), light.direction);
  Aabb bounds = scene.bounds().transformed(lightFromWorld);
  if (bounds.empty()) bounds = Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)};
  const float span = std::max(bounds.hi.z - bounds.lo.z, 1.0f);
  const float step = std::exp2(std::ceil(std::log2(span))) / kDepthStepsPerSpan;
  const float nearM = (std::floor(-bounds.hi.z / step) - 1.0f) * step;
  const float farM = (std::ceil(-bounds.lo.z / step) + 1.0f) * step;
  const glm::vec3 centre = glm::vec3(lightFromWorld * glm::vec4(camera.position, 1.0f));
  LightFrusta f;
  const int levels = paramInt("virtual.levels");
  for (int level = 0; level < levels; ++level) {
    const float extentM = param("virtual.firstLevelM") * std::exp2(static_cast<float>(level));
    const double pageM = static_cast<double>(extentM) / layout.pagesPerSide();
    // The square around the camera, its corner on the page grid of its level.
    const glm::dvec2 lo = glm::floor((glm::dvec2(centre) - 0.5 * static_cast<double>(extentM)) / pageM) * pageM;
    ShadowView v;
    v.viewFromWorld = lightFromWorld;
    v.nearM = nearM;
    v.farM = farM;
    v.perspective = false;
    v.extent = glm::vec2(extentM);
    v.clipFromWorld = glm::orthoRH_ZO(static_cast<float>(lo.x), static_cast<float>(lo.x) + extentM, static_cast<float>(lo.y),
                                      static_cast<float>(lo.y) + extentM, nearM, farM) *
                      lightFromWorld;
    v.depthPlane = linearDepthPlane(lightFromWorld, nearM, farM);
    f.views.push_back(v);
  }
  return f;
}

}  // namespace penumbra
