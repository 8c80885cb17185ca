#include "techniques/sdf/SdfFilter.h"

#include "frame/FrameContext.h"
#include "techniques/sdf/sdf.shared.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

namespace penumbra {
namespace {

constexpr std::string_view kKModes[] = {"manual", "light"};
constexpr std::string_view kEstimators[] = {"classic", "improved"};
constexpr std::string_view kPenumbrae[] = {"outer", "centered"};
static_assert(PN_SDF_K_MANUAL == 0 && PN_SDF_K_LIGHT == 1, "kKModes follows the PN_SDF_K_* order");
static_assert(PN_SDF_ESTIMATOR_CLASSIC == 0 && PN_SDF_ESTIMATOR_IMPROVED == 1, "kEstimators follows PN_SDF_ESTIMATOR_*");
static_assert(PN_SDF_PENUMBRA_OUTER == 0 && PN_SDF_PENUMBRA_CENTERED == 1, "kPenumbrae follows PN_SDF_PENUMBRA_*");

/// k for a light of size 0 (a point or a delta-direction sun) in light mode: a clearance of
/// 1/1000 of the ray length already counts as lit, i.e. a hard shadow up to a 1 mm band per metre.
constexpr float kPointLightK = 1000.0f;

constexpr std::string_view kNoBaker =
    "no distance-field baker is installed (link Penumbra::bake and call penumbra::sdf::installEmbreeBaker(), or install "
    "your own with penumbra::sdf::setBaker)";

constexpr ParamDesc kParams[] = {
    {"sdf.kMode", "k from", "light: k = 1/tan(angular radius of the light seen from the receiver), so the scene's light size "
     "sets the penumbra; manual: k = sdf.k", "", PN_SDF_K_LIGHT, 0, 1, 1, kKModes},
    {"sdf.k", "k", "penumbra hardness in manual mode: V = min(k·d/t, 1) for free distance d at ray length t; larger = harder", "factor",
     16.0f, 0.5f, 1000.0f, 0.0f},
    {"sdf.maxSteps", "Max steps", "sphere-tracing steps per pixel; a ray still marching after them counts as unoccluded beyond", "steps",
     128, 1, 1024, 1},
    {"sdf.epsilon", "Epsilon", "hit distance and smallest step, in voxels: a sample closer than this to a caster ends the march in "
     "shadow (outer mode)", "voxels", 0.1f, 0.001f, 2.0f, 0.0f},
    {"sdf.startOffset", "Start offset", "the march starts this many voxels off the receiver along its geometric normal, out of "
     "the field's blur around its own surface; larger values lift the start over nearby casters (leaks at contacts)", "voxels",
     0.25f, 0.0f, 8.0f, 0.0f},
    {"sdf.estimator", "Estimator", "classic: k·d/t at each sample; improved: at the closest approach estimated from the previous "
     "sample's distance (Aaltonen 2018), less banding", "", PN_SDF_ESTIMATOR_CLASSIC, 0, 1, 1, kEstimators},
    {"sdf.penumbra", "Penumbra", "outer: V = min(k·d/t, 1), the penumbra grows outward from the hard shadow; centered: the "
     "march goes on through casters (d < 0) and V is the visible part of a disc light at that angle, half inside, half outside", "",
     PN_SDF_PENUMBRA_CENTERED, 0, 1, 1, kPenumbrae},
    {"sdf.resolution", "Resolution", "voxels along the longest side of the casters' bounds (cubic voxels); changing it rebakes", "voxels",
     sdf::kDefaultResolution, sdf::kMinResolution, sdf::kMaxResolution, 1},
};

}  // namespace

SdfFilter::SdfFilter() : Filter(kParams) {}

std::string SdfFilter::incompatibility(std::string_view, const Light&) const {
  return sdf::baker() ? std::string() : std::string(kNoBaker);
}

void SdfFilter::renderShadowMaps(FrameContext& frame) {
  const int resolution = frame.paramInt("sdf.resolution");
  PN_CHECK(frame.casterGeometry().has_value(),
           "sdf bakes the casters' triangles on the CPU: give them to Penumbra (Shadows::setCasterGeometry)");
  const std::span<const CasterGeometry> casters = *frame.casterGeometry();
  const uint64_t key = sdf::cacheKey(casters, resolution);
  if (mHaveField && key == mKey) return;
  sdf::BakeOptions options;
  options.resolution = resolution;
  options.verbose = true;  // every bake reports its time and memory on stderr; a cache hit is silent
  const sdf::Baker& baker = sdf::baker();
  PN_CHECK(baker, kNoBaker);
  setField(baker(casters, options));
  mKey = key;
}

void SdfFilter::setField(const sdf::SdfVolume& volume) {
  mHaveField = true;
  ++mUploads;
  mKey = 0;
  mGrid = volume;
  mGrid.distances.clear();
  mGrid.distances.shrink_to_fit();
  // Without a grid (no casters, or only sheets) a valid 1³ texture stays bound; the shader does
  // not read it then.
  const glm::ivec3 dims = volume.hasGrid() ? volume.dims : glm::ivec3(1);
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  PN_CHECK(dims.x <= max3d && dims.y <= max3d && dims.z <= max3d,
           fmt::format("sdf: a {}x{}x{} field exceeds the driver's 3D texture limit of {}; lower sdf.resolution", dims.x,
                       dims.y, dims.z, max3d));
  mField = gl::Texture("sdf field", {GL_TEXTURE_3D, GL_R32F, dims.x, dims.y, dims.z, 1});
  mField.setSampling(GL_LINEAR, GL_LINEAR);
  mSlice = gl::Texture("sdf middle z slice", {GL_TEXTURE_2D, GL_R32F, dims.x, dims.y, 1, 1});
  mSlice.setSampling(GL_NEAREST, GL_NEAREST);
  const float none = 0.0f;
  const float* data = volume.hasGrid() ? volume.distances.data() : &none;
  glTextureSubImage3D(mField.id(), 0, 0, 0, 0, dims.x, dims.y, dims.z, GL_RED, GL_FLOAT, data);
  const size_t slice = static_cast<size_t>(dims.z / 2) * static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y);
  glTextureSubImage2D(mSlice.id(), 0, 0, 0, dims.x, dims.y, GL_RED, GL_FLOAT, volume.hasGrid() ? data + slice : data);
}

gpu::SdfUniforms SdfFilter::uniforms(const Parameterized& p) const {
  gpu::SdfUniforms u{};
  u.gridLo = glm::vec4(mGrid.lo, mGrid.voxelM);
  u.gridSize = glm::vec4(mGrid.size(), mGrid.hasGrid() ? 1.0f : 0.0f);
  const Aabb gridCasters = mGrid.gridCasterBounds();
  if (mGrid.hasGrid()) {
    u.gridCasterLo = glm::vec4(gridCasters.lo, 0.0f);
    u.gridCasterHi = glm::vec4(gridCasters.hi, 0.0f);
  }
  if (!mGrid.empty()) {
    // Padded like the grid: a sheet's bounds are flat, and a ray must be able to cross them.
    const glm::vec3 pad(static_cast<float>(sdf::kPadVoxels) * mGrid.voxelM);
    const Aabb casters = mGrid.casterBounds();
    u.castersLo = glm::vec4(casters.lo - pad, 0.0f);
    u.castersHi = glm::vec4(casters.hi + pad, 0.0f);
  }
  u.march = glm::vec4(p.param("sdf.k"), p.param("sdf.epsilon"), p.param("sdf.startOffset"), kPointLightK);
  u.mode = glm::ivec4(p.paramInt("sdf.maxSteps"), p.paramInt("sdf.kMode"), p.paramInt("sdf.estimator"), p.paramInt("sdf.penumbra"));
  const size_t sheetTriangles = mGrid.sheets.size() / 3;
  PN_ASSERT(sheetTriangles <= static_cast<size_t>(PN_SDF_MAX_SHEET_TRIANGLES));
  u.sheetInfo = glm::ivec4(static_cast<int>(sheetTriangles), 0, 0, 0);
  for (size_t i = 0; i < mGrid.sheets.size(); ++i) u.sheetVertices[i] = glm::vec4(mGrid.sheets[i], 1.0f);
  return u;
}

void SdfFilter::computeVisibility(FrameContext& frame) {
  PN_ASSERT(mHaveField);
  frame.setFilterBlock(uniforms(frame.params()));
  mField.bindUnit(PN_TEX_FILTER0);
  frame.dispatchScreen(frame.visibilityProgram("techniques/sdf/sdf.glsl"));
}

std::vector<DebugImage> SdfFilter::debugImages() const { return {{"sdf-slice", &mSlice, "signed distance to the nearest caster (m) in the field's middle z slice; < 0 inside"}};
}

std::vector<OneOffCost> SdfFilter::oneOffCosts() const {
  if (!mHaveField) return {};
  return {{fmt::format("distance-field bake, {}x{}x{} voxels", mGrid.dims.x, mGrid.dims.y, mGrid.dims.z),
           mGrid.stats.bakeSeconds, mGrid.stats.fromCache}};
}

}  // namespace penumbra
