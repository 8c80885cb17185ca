#pragma once
// What a Filter may use during a frame: the light and its views, the shader library, the caster
// draw, the full-screen dispatch over the surfaces and its own uniform block. Filters never
// touch the core's internals; the core never asks which filter it runs.
#include "frame/CasterSet.h"
#include "gl/Objects.h"
#include "frame/PassTimer.h"
#include "frame/ScreenTarget.h"
#include "frame/ShadowMaps.h"
#include "shader/ShaderLibrary.h"

#include "frame/Projection.h"
#include <penumbra/Scene.h>

#include <glm/glm.hpp>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace penumbra {

class VirtualPages;  // frame/VirtualPages.h: a paged projection's pages

/// The light's kind as the shaders name it: PN_LIGHT_SUN, PN_LIGHT_SPOT or PN_LIGHT_POINT.
int shaderLightKind(const Light& light);

/// Where the visibility pass finds each pixel's surface (bound at PN_TEX_GBUF_POSITION and
/// PN_TEX_GBUF_GEONORMAL by the core before the pass).
enum class SurfaceSource {
  Position,  ///< a world-position texture (w > 0.5 = geometry): Penumbra's own G-buffer
  Depth,     ///< the camera's depth texture, unprojected with FrameUniforms::worldFromClip
};

/// What the frame's surfaces and camera are, as the screen passes' programs are built for them.
struct SurfaceFacts {
  SurfaceSource source = SurfaceSource::Position;
  /// No normal texture: each pixel's geometric normal is reconstructed from its neighbours'
  /// positions (PN_NORMALS_FROM_POSITIONS, common/visibility.glsl).
  bool normalsFromPositions = false;
  /// The camera is orthographic: its rays are parallel (PN_CAMERA_ORTHOGRAPHIC).
  bool orthographicCamera = false;
};
/// How a screen pass reads such surfaces (common/visibility.glsl): PN_SURFACE_FROM_DEPTH,
/// PN_NORMALS_FROM_POSITIONS, PN_CAMERA_ORTHOGRAPHIC, each where it holds.
ShaderDefines surfaceDefines(const SurfaceFacts& surface);

/// Cached shadow maps across frames (MapUpdates): how many layers renderViews restored and
/// rendered.
struct MapCacheState {
  size_t restored = 0, rendered = 0;
};

/// Everything a frame's FrameContext refers to; owned by the core, alive for the frame.
struct FrameResources {
  const Light& light;
  /// The filter's parameter values for this light (its technique's, Technique::filterValues).
  const Parameterized& params;
  /// The casters' triangles on the CPU, when the caller gave them (Shadows::setCasterGeometry).
  std::optional<std::span<const CasterGeometry>> casterGeometry;
  const LightFrusta& frusta;
  int mapSize;
  glm::ivec2 screen;
  SurfaceFacts surface;
  ShaderLibrary& shaders;
  const CasterSet& casters;
  gl::Buffer& filterBlock;
  PassTimer& timer;
  const gl::Texture* visibility;  ///< a 2D array: one layer per light
  int visibilityLayer = 0;        ///< this frame's light
  MapCacheState* mapCache = nullptr;  ///< nullptr: this light's maps are not cached
  /// Per view, 1 where its map is kept as an earlier frame drew it (MapUpdates::Budget; the
  /// frusta then hold the view it was drawn with); empty: every map is drawn.
  std::span<const uint8_t> keptViews = {};
  /// The visibility pass's target: this frame's light's layer of `visibility` (ScreenTarget).
  const ScreenTarget* visibilityTarget = nullptr;
  /// A paged projection's pages (marked for this frame); nullptr: whole maps.
  VirtualPages* pages = nullptr;
  /// What the filter's maps hold of the translucent casters: drawn as opaque (the default), or
  /// left out when the translucent add-on tints V by them (docs/translucent.md).
  CasterSet::Translucent translucentCasters = CasterSet::Translucent::AsOpaque;
  /// The visibility array holds RGB (RGBA32F, alpha unused) rather than one channel (R32F): the
  /// screen passes are built with PN_VISIBILITY_RGB.
  bool colourVisibility = false;
  /// The shadow passes dither the translucent casters by their opacity (stochastic transparency,
  /// translucent.method=stochastic): renderViews draws them with the pass built with
  /// PN_DITHER_TRANSLUCENT (common/material.glsl), and such maps are never cached.
  bool ditherTranslucent = false;
};

class FrameContext {
public:
  explicit FrameContext(const FrameResources& r)
      : mLight(r.light), mParams(r.params), mCasterGeometry(r.casterGeometry), mFrusta(r.frusta), mMapSize(r.mapSize), mScreen(r.screen),
        mSurface(r.surface), mShaders(r.shaders), mCasters(r.casters), mFilterBlock(r.filterBlock), mTimer(r.timer),
        mVisibility(r.visibility), mVisibilityLayer(r.visibilityLayer), mMapCache(r.mapCache), mKeptViews(r.keptViews),
        mVisibilityTarget(r.visibilityTarget), mPages(r.pages), mTranslucentCasters(r.translucentCasters),
        mColourVisibility(r.colourVisibility), mDitherTranslucent(r.ditherTranslucent) {}

  /// The casters' triangles on the CPU (Shadows::setCasterGeometry); none when the caller gave
  /// none. Only techniques that bake the geometry (sdf) need them.
  std::optional<std::span<const CasterGeometry>> casterGeometry() const { return mCasterGeometry; }
  const Light& light() const { return mLight; }
  /// The filter's parameters for this light: its technique's values (the filter holds none).
  const Parameterized& params() const { return mParams; }
  float param(std::string_view key) const { return mParams.param(key); }
  int paramInt(std::string_view key) const { return mParams.paramInt(key); }
  const LightFrusta& frusta() const { return mFrusta; }
  int viewCount() const { return static_cast<int>(mFrusta.views.size()); }
  /// Texels per side of each view's map (a paged projection's: its virtual size).
  int mapSize() const { return mMapSize; }
  /// The views are paged (a virtual projection): their maps are a pool of pages read through a
  /// page table (common/shadow.glsl: fetchMapDepth), so no filter may read them as whole
  /// textures (mips, summed-area tables, pyramids, hardware 2x2 comparisons).
  bool paged() const { return mPages != nullptr; }
  /// The paged views' pages (null when not paged).
  const VirtualPages* pages() const { return mPages; }
  /// Makes `maps` the storage the views are drawn into (depth only): a layer of mapSize()² per
  /// view, or for paged views the pool of pages.
  void ensureMaps(ShadowMapArray& maps, const std::string& label);
  const CasterSet& casters() const { return mCasters; }
  glm::ivec2 screen() const { return mScreen; }
  ShaderLibrary& shaders() { return mShaders; }
  PassTimer& timer() { return mTimer; }
  /// The visibility array (a layer per light) and this frame's light's layer in it.
  const gl::Texture& visibility() const { return *mVisibility; }
  int visibilityLayer() const { return mVisibilityLayer; }

  const gl::Program& program(const ProgramDesc& desc) { return mShaders.program(desc); }
  /// The programs of a shadow pass: one for alpha-tested casters and one for opaque casters
  /// (compiled with PN_OPAQUE_CASTERS: no alpha test, so early depth tests stay on).
  struct ShadowPrograms {
    const gl::Program* masked;
    const gl::Program* opaque;
    /// With FrameResources::ditherTranslucent: the same pass built with PN_DITHER_TRANSLUCENT,
    /// which renderViews draws the translucent casters with (the others keep the plain pass and
    /// its early depth test); null otherwise.
    const gl::Program* ditherMasked = nullptr;
    const gl::Program* ditherOpaque = nullptr;
  };
  /// Shadow-pass programs: passes/geometry.vert.glsl + `fragment` (default: linear depth only).
  /// The default depth-only pass over orthographic views (a sun's uniform map or cascades) is
  /// built with PN_LINEAR_RASTER_DEPTH: linear light depth is affine there, so the rasteriser's
  /// own depth (the view's depth plane as clip z) is what the map stores and no fragment writes
  /// gl_FragDepth.
  ShadowPrograms shadowProgram(std::string_view fragment = kDepthOnlyFragment, const ShaderDefines& defines = {});
  static constexpr std::string_view kDepthOnlyFragment = "passes/shadow_depth.frag.glsl";
  /// Visibility program: the filter's GLSL file (defining shadowVisibility) + the pass's main,
  /// built for this frame: frameDefines(), the surfaces (surfaceDefines()), points mode, the
  /// filter's compile-time parameters (ParamDesc::define), then the filter's own `defines`. Over
  /// the screen it is a fragment program (fullScreenProgram: the full-screen triangle drawn into
  /// the light's visibility layer); in points mode a compute program. Each variant is compiled
  /// once (the library's cache).
  const gl::Program& visibilityProgram(std::string_view filterFile, const ShaderDefines& defines = {});
  /// A screen pass of the frame's own (one GLSL file with its main) over the same surfaces as
  /// the visibility pass, built like it: frameDefines(), the SurfaceSource, `params`' constants.
  const gl::Program& screenProgram(std::string_view file, const Parameterized& params);
  /// What the frame is made of, as compile-time constants (common/shadow.glsl): PN_SHADOW_VIEWS,
  /// PN_LIGHT_KIND, PN_VIEWS_PERSPECTIVE and PN_VIEWS_WARPED (when all views agree), PN_CASCADE_BLEND;
  /// PN_VISIBILITY_RGB when the visibility array holds colour.
  ShaderDefines frameDefines() const;
  /// The visibility array holds RGB (FrameResources::colourVisibility).
  bool colourVisibility() const { return mColourVisibility; }
  /// What the filter's maps hold of the translucent casters (FrameResources::translucentCasters).
  CasterSet::Translucent translucentCasters() const { return mTranslucentCasters; }
  /// How the screen passes read the surfaces (common/visibility.glsl): PN_SURFACE_FROM_DEPTH,
  /// PN_NORMALS_FROM_POSITIONS, PN_CAMERA_ORTHOGRAPHIC, each where it holds.
  ShaderDefines surfaceDefines() const;

  /// Renders every view into its layer of `maps` with `program`: depth cleared to 1 (far),
  /// colour cleared to `clearColor`; depth test LESS, depth clamp on (casters in front of the
  /// near plane still cast), no culling (thin and open casters cast from both sides). With cached
  /// maps each layer whose key (its view's matrix and depth plane, the programs, the filter
  /// block, the clear colour, the static casters) is unchanged is restored from its cache and
  /// only the dynamic casters are drawn over it. A layer the frame keeps (FrameResources::
  /// keptViews) is left as it is, once it has been drawn. Paged views: the pages the frame
  /// needs that are not resident and valid are drawn into their tiles (VirtualPages::render).
  /// The translucent casters are drawn as FrameResources::translucentCasters says (as opaque,
  /// or left out).
  void renderViews(ShadowMapArray& maps, const ShadowPrograms& programs, const glm::vec4& clearColor = glm::vec4(1.0f));
  /// The translucent add-on's maps: per view, the opaque casters' depth (`opaque`, colour writes
  /// off), then the translucent casters drawn with `translucent` over it, depth-tested and not
  /// writing depth, their colour output multiplied into RGB and their alpha output kept by its
  /// minimum (blend equation MIN). Colour cleared to 1, depth to 1 (far). With cached maps each
  /// layer is restored and stored as renderViews does (key: both programs, the size, the static
  /// casters, the view); kept views are drawn again with the view they were drawn with.
  void renderTranslucentViews(ShadowMapArray& maps, const ShadowPrograms& opaque, const ShadowPrograms& translucent);
  /// Per view, the sum over the translucent casters alone (CasterSet::Translucent::Only) of
  /// what `program` outputs (additive blending; colour cleared to 0, no depth test): every
  /// translucent surface over the texel counts, in any order (msm.translucent's moments). Cached
  /// like renderTranslucentViews.
  void sumTranslucentViews(ShadowMapArray& maps, const ShadowPrograms& program);
  /// Draws the full-screen fragment `program` (a visibilityProgram) into the light's visibility
  /// layer, multiplying what the visibility pass wrote there, channel by channel.
  void multiplyVisibility(const gl::Program& program) const;

  /// Uploads the filter's uniform block (bound at PN_UBO_FILTER for the rest of the frame).
  template <class T> void setFilterBlock(const T& block) { setFilterBlockBytes(&block, sizeof(T)); }
  void setFilterBlockBytes(const void* data, size_t bytes);

  /// Runs `program` once per pixel (the surfaces are bound): a fragment program (the visibility
  /// pass) draws into the light's visibility layer; a compute program (screenProgram) gets the
  /// visibility image bound, write-only or, with readVisibility, read-write for a pass that
  /// changes what the visibility pass wrote. In points mode (setPoints), runs it once per point
  /// instead (see visibilityProgram).
  void dispatchScreen(const gl::Program& program, bool readVisibility = false) const;

  /// Points mode, used by Renderer::visibilityAt: visibilityProgram() compiles the pass with
  /// PN_VISIBILITY_POINTS (positions from `points`, a PointBlock of shared/VisibilityPoints.h,
  /// V into `visibility`, one float per point) and dispatchScreen() runs over the points. A
  /// filter needs no code for it as long as its visibility goes through those two calls.
  void setPoints(const gl::Buffer* points, const gl::Buffer* visibility, int count) {
    mPoints = points;
    mPointVisibility = visibility;
    mPointCount = count;
  }
  /// True in points mode: there is no screen, so per-pixel debug outputs are left alone.
  bool pointsMode() const { return mPoints != nullptr; }
  /// Runs `program` over a width × height grid in groups of `group`².
  static void dispatch2D(const gl::Program& program, int width, int height, int group);

private:
  const Light& mLight;
  const Parameterized& mParams;
  std::optional<std::span<const CasterGeometry>> mCasterGeometry;
  const LightFrusta& mFrusta;
  int mMapSize;
  glm::ivec2 mScreen;
  SurfaceFacts mSurface;
  ShaderLibrary& mShaders;
  const CasterSet& mCasters;
  gl::Buffer& mFilterBlock;
  PassTimer& mTimer;
  const gl::Texture* mVisibility;
  int mVisibilityLayer;
  MapCacheState* mMapCache;
  std::span<const uint8_t> mKeptViews;
  const ScreenTarget* mVisibilityTarget;
  VirtualPages* mPages;
  CasterSet::Translucent mTranslucentCasters;
  bool mColourVisibility;
  bool mDitherTranslucent;
  const gl::Buffer* mPoints = nullptr;
  const gl::Buffer* mPointVisibility = nullptr;
  int mPointCount = 0;
};

}  // namespace penumbra
