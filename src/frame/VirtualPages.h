#pragma once
// A paged projection's pages (docs/virtual.md), one light's: which pages of its virtual maps this
// frame's pixels need (a pass over the surfaces that marks them, passes/virtual_pages.comp.glsl,
// and a read back of the list), where each lives (a tile of the pool, the filter's depth map,
// kept across frames: least recently needed out first), which must be drawn (new, invalid, or
// under a dynamic caster that moved) and the page table the shaders read them through
// (common/shadow.glsl: fetchMapDepth). A page stays valid while what it was drawn from stays:
// the light's rotation and depth range, its level's place on the page grid, the static casters
// and the shadow pass. With cached map updates (MapUpdates::cached) each tile's static casters
// are kept in a copy, so a dynamic caster that moves redraws only itself over the pages it
// touched or touches; without, those pages are drawn anew whole.
#include "frame/CasterSet.h"
#include "frame/Projection.h"
#include "frame/ShadowMaps.h"
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace penumbra {

class FrameContext;

/// What a paged light's pages did in its last frame.
struct PageStats {
  int needed = 0;     ///< pages this frame's pixels marked
  int drawn = 0;      ///< pages rasterised this frame (new, invalid, or under a moved dynamic caster)
  int resident = 0;   ///< valid pages the pool holds after the frame (this frame's and earlier ones')
  int missing = 0;    ///< marked pages the full pool could not take (a coarser level served them)
  int poolPages = 0;  ///< the pool's capacity
  int levels = 0;     ///< views (clipmap levels)
  int64_t poolBytes = 0;  ///< the pool's depth storage (and the static copy's, when kept)
};

class VirtualPages {
public:
  /// This frame's layout and views (what the projection made) and how many virtual maps they are,
  /// each views.size() / maps levels, map after map (a point light's cube: 6 faces; else 1), the
  /// camera pixel's width per metre of distance (the pixel's width, an orthographic camera) and
  /// whether static casters are kept apart (cached map updates). Tiles are made or remade here
  /// when the layout changed.
  void beginFrame(const PageLayout& layout, const LightFrusta& frusta, int maps, float pixelWidthPerM, bool keepStatic);
  /// The marking pass over the surfaces (bound by the caller, as for the visibility pass), its
  /// read back, and the plan: each needed page's tile, found or taken. Timed by the caller.
  void mark(FrameContext& frame);
  /// Draws the pages the plan found missing or invalid into `pool` (made by FrameContext::
  /// ensureMaps), and uploads the page table.
  void render(FrameContext& frame, ShadowMapArray& pool, GLuint opaqueProgram, GLuint maskedProgram, const CasterSet& casters,
              uint64_t passKey);
  /// Binds the page table and the level block where common/shadow.glsl reads them.
  void bind() const;
  /// The layout's constants for every pass that reads the pages (PN_VIRTUAL_PAGES, …).
  ShaderDefines defines() const;
  int poolSide() const { return mTilesPerSide * mLayout.pageSize; }
  int pageSize() const { return mLayout.pageSize; }
  int poolLayers() const { return mPoolLayers; }
  const PageStats& stats() const { return mStats; }
  /// The pages drawn in the last frame: (level, x, y) on the level's grid of that frame.
  const std::vector<glm::ivec3>& drawnPages() const { return mDrawnPages; }

private:
  struct Tile {
    uint64_t page = 0;        ///< packed (level, global page x, y); 0 = free
    int64_t lastNeeded = -1;  ///< frame it was last needed in
    bool valid = false;       ///< its static casters (or all of them, without a static copy) are drawn
    bool dynamicStale = false;  ///< a dynamic caster moved over it since its dynamic casters were drawn
  };
  struct Draw {
    int tile;
    bool whole;  ///< clear and draw everything; else restore the static copy and draw the dynamic casters
  };
  static uint64_t packPage(int level, int64_t x, int64_t y);
  void unpackPage(uint64_t page, int& level, int64_t& x, int64_t& y) const;
  /// The rectangle of page (x, y) of view `level`'s grid in the space casters are culled in: the
  /// sun's light space (m), a spot's (a point light's face's) level 0 uv.
  glm::dvec4 pageRect(int level, int64_t x, int64_t y) const;
  /// A world box's rectangle in that space of virtual map `map` (cullRect ∩ pageRect empty: the
  /// box is off the page).
  glm::dvec4 cullRect(const Aabb& world, int map) const;
  /// Every world box's cullRect in every virtual map, map after map.
  std::vector<glm::dvec4> cullRects(std::span<const Aabb> world) const;
  int mapOf(int view) const { return view / mMapLevels; }
  void dropAll();
  void invalidateUnder(const Aabb& world);
  int takeTile(uint64_t page);

  PageLayout mLayout;
  int mLevels = 0;
  int mTilesPerSide = 0, mPoolLayers = 0;
  bool mKeepStatic = false;
  float mPixelWidthPerM = 0.0f;
  glm::mat4 mLightFromWorld{1.0f};
  bool mPerspective = false;            ///< perspective views in mips (a spot's, a point light's faces; else the sun's clipmap)
  int mMapLevels = 0;                   ///< levels of each virtual map (views / maps)
  std::vector<glm::mat4> mMapClip;      ///< per virtual map (a spot's one, a point light's faces): its level 0's clipFromWorld
  std::vector<double> mLevelExtentM;      ///< per level: its square's width (m; a spot's: at 1 m from the light)
  std::vector<glm::i64vec2> mLevelOrigin;  ///< per level: its square's corner, in pages of its grid
  uint64_t mContentKey = 0;               ///< what every page depends on (beginFrame + render's pass key)
  uint64_t mPassKey = 0;
  GLuint mPoolId = 0;
  std::vector<Tile> mTiles;
  std::unordered_map<uint64_t, int> mTileOf;
  std::vector<CasterSet::Placement> mPlacements;  ///< the casters as the last frame drew them
  std::vector<Draw> mDraws;
  std::vector<glm::ivec3> mDrawnPages;
  int64_t mFrame = 0;
  PageStats mStats;
  std::vector<uint32_t> mTable, mUploadedTable;
  gl::Texture mPageTable;
  gl::Texture mStaticCopy;
  gl::Buffer mFlags, mList, mBlock;
  std::vector<uint8_t> mCasterMask;
};

}  // namespace penumbra
