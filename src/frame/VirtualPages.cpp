#include "frame/VirtualPages.h"

#include "base/Hash.h"
#include "frame/FrameContext.h"
#include "gl/Debug.h"
#include "shared/Bindings.h"
#include "shared/VirtualPages.h"

#include <penumbra/Error.h>
#include <penumbra/MapSizes.h>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace penumbra {
namespace {

constexpr int kCoordBits = 28;  // per page axis: ±2^27 pages of a level's grid
constexpr int64_t kCoordBias = int64_t{1} << (kCoordBits - 1);
constexpr uint64_t kCoordMask = (uint64_t{1} << kCoordBits) - 1;

}  // namespace

uint64_t VirtualPages::packPage(int level, int64_t x, int64_t y) {
  // level + 1 in the top bits: no page packs to 0, the free tile's mark.
  return (static_cast<uint64_t>(level + 1) << (2 * kCoordBits)) | (static_cast<uint64_t>(x + kCoordBias) & kCoordMask) << kCoordBits |
         (static_cast<uint64_t>(y + kCoordBias) & kCoordMask);
}

void VirtualPages::unpackPage(uint64_t page, int& level, int64_t& x, int64_t& y) const {
  level = static_cast<int>(page >> (2 * kCoordBits)) - 1;
  x = static_cast<int64_t>((page >> kCoordBits) & kCoordMask) - kCoordBias;
  y = static_cast<int64_t>(page & kCoordMask) - kCoordBias;
}

glm::dvec4 VirtualPages::pageRect(int level, int64_t x, int64_t y) const {
  if (mPerspective) {
    // Level l's uv is 2^-l · level 0's: its page (x, y) spans 2^l / pagesPerSide of level 0's uv.
    const double w = std::exp2(static_cast<double>(level % mMapLevels)) / mLayout.pagesPerSide();
    return {static_cast<double>(x) * w, static_cast<double>(y) * w, static_cast<double>(x + 1) * w, static_cast<double>(y + 1) * w};
  }
  const double pageM = mLevelExtentM[static_cast<size_t>(level)] / mLayout.pagesPerSide();
  return {static_cast<double>(x) * pageM, static_cast<double>(y) * pageM, static_cast<double>(x + 1) * pageM,
          static_cast<double>(y + 1) * pageM};
}

glm::dvec4 VirtualPages::cullRect(const Aabb& world, int map) const {
  if (!mPerspective) {
    const Aabb b = world.transformed(mLightFromWorld);
    return {b.lo.x, b.lo.y, b.hi.x, b.hi.y};
  }
  // A spot's (a face's) page is a sub-frustum: a box touches it when its corners' projection (a
  // convex hull's bounds, all corners in front of the light) meets the page's uv rectangle. A box
  // that reaches behind the light's near plane touches every page.
  constexpr double kInf = 1e30;
  glm::dvec4 r(kInf, kInf, -kInf, -kInf);
  for (const glm::vec3& c : world.corners()) {
    const glm::vec4 clip = mMapClip[static_cast<size_t>(map)] * glm::vec4(c, 1.0f);
    if (clip.w <= 1e-6f) return {-kInf, -kInf, kInf, kInf};
    const glm::dvec2 uv = glm::dvec2(clip.x, clip.y) / static_cast<double>(clip.w) * 0.5 + 0.5;
    r = glm::dvec4(std::min(r.x, uv.x), std::min(r.y, uv.y), std::max(r.z, uv.x), std::max(r.w, uv.y));
  }
  return r;
}

std::vector<glm::dvec4> VirtualPages::cullRects(std::span<const Aabb> world) const {
  std::vector<glm::dvec4> rects;
  rects.reserve(mMapClip.size() * world.size());
  for (size_t map = 0; map < mMapClip.size(); ++map)
    for (const Aabb& b : world) rects.push_back(cullRect(b, static_cast<int>(map)));
  return rects;
}

void VirtualPages::dropAll() {
  for (Tile& t : mTiles) t = {};
  mTileOf.clear();
}

void VirtualPages::beginFrame(const PageLayout& layout, const LightFrusta& frusta, int maps, float pixelWidthPerM, bool keepStatic) {
  const int levels = static_cast<int>(frusta.views.size());
  PN_CHECK(maps >= 1 && levels % maps == 0, fmt::format("VirtualPages: {} views are not {} virtual maps of equal levels", levels, maps));
  if (!(layout == mLayout) || levels != mLevels || keepStatic != mKeepStatic || mTiles.empty()) {
    mLayout = layout;
    mLevels = levels;
    mKeepStatic = keepStatic;
    const int maxSide = gl::maxTextureSize();
    mTilesPerSide = std::min(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(layout.poolPages)))), maxSide / layout.pageSize);
    mPoolLayers = (layout.poolPages + mTilesPerSide * mTilesPerSide - 1) / (mTilesPerSide * mTilesPerSide);
    mTiles.assign(static_cast<size_t>(layout.poolPages), {});
    mTileOf.clear();
    mStaticCopy = {};
    const int pages = layout.pagesPerSide();
    const size_t entries = static_cast<size_t>(levels) * static_cast<size_t>(pages) * static_cast<size_t>(pages);
    mPageTable = gl::Texture("virtual page table", {GL_TEXTURE_2D_ARRAY, GL_R32UI, pages, pages, levels, 1});
    mPageTable.setSampling(GL_NEAREST, GL_NEAREST);
    mTable.assign(entries, 0u);
    mUploadedTable.assign(entries, 1u);  // differs from every table: the first frame uploads
    mFlags = gl::Buffer("virtual page flags", entries * sizeof(uint32_t));
    mList = gl::Buffer("virtual page list", (entries + 1) * sizeof(uint32_t));
    mBlock = gl::Buffer("virtual pages block", sizeof(gpu::PagesUniforms));
    gl::throwIfGlError(fmt::format("the virtual pages' tables ({} levels of {}² pages)", levels, pages).c_str());
  }
  mPixelWidthPerM = pixelWidthPerM;
  // What every page depends on besides the casters and the pass: the light's rotation, the depth
  // range and each level's size. A level's place (its corner on its page grid) moves with the
  // camera and changes no page.
  Hasher h;
  h.value(frusta.views.front().viewFromWorld);
  h.value(frusta.views.front().depthPlane);
  mLightFromWorld = frusta.views.front().viewFromWorld;
  mPerspective = frusta.views.front().perspective;
  mMapLevels = levels / maps;
  mMapClip.clear();
  for (int map = 0; map < maps; ++map) {
    mMapClip.push_back(frusta.views[static_cast<size_t>(map * mMapLevels)].clipFromWorld);
    if (mPerspective) h.value(mMapClip.back());  // a spot's view (a face's): its place, cone and depth range
  }
  mLevelExtentM.assign(static_cast<size_t>(levels), 0.0);
  mLevelOrigin.assign(static_cast<size_t>(levels), glm::i64vec2(0));
  for (int l = 0; l < levels; ++l) {
    const ShadowView& v = frusta.views[static_cast<size_t>(l)];
    h.value(v.extent);
    if (mPerspective) {
      // Views in mips (VirtualProjection::perspectiveMips): no level slides; its extent is at 1 m.
      mLevelExtentM[static_cast<size_t>(l)] = std::max(v.extent.x, v.extent.y);
      continue;
    }
    const double extent = v.extent.x;
    const double pageM = extent / layout.pagesPerSide();
    // clip.x = 2·(x − lo) / extent − 1 with the view's eye at the origin: its translation t = −2·lo / extent − 1.
    const glm::dvec2 lo = -(glm::dvec2(v.clipFromWorld[3]) + 1.0) * (0.5 * extent);
    mLevelExtentM[static_cast<size_t>(l)] = extent;
    mLevelOrigin[static_cast<size_t>(l)] = glm::i64vec2(glm::round(lo / pageM));
  }
  if (const uint64_t key = h.digest(); key != mContentKey) {
    mContentKey = key;
    dropAll();
  }
  gpu::PagesUniforms u{};
  u.lod = glm::vec4(static_cast<float>(std::log2(mLevelExtentM.front() / layout.virtualSize)), pixelWidthPerM, layout.levelBias,
                    layout.marginTexels);
  // A perspective view's level is read by pixels while it holds the view in at least
  // kMinDefaultsMapSizeTexels texels a side: a coarser one holds it in fewer texels than the least
  // map the defaults are held to, and the filters' radii, bounded in texels (pcss's search up to
  // 96), would span it (room's spot at 320×180 read a 128-texel level: pcss RMSE 0.122 against
  // uniform's 0.011). The coarser levels, down to one page, serve reads past the resident pages (a
  // ray's far steps, a wide search), which always find that last page.
  const int fitting = static_cast<int>(std::bit_width(static_cast<unsigned>(std::max(layout.virtualSize / kMinDefaultsMapSizeTexels, 1))));
  const int readLevels = mPerspective ? std::min(mMapLevels, fitting) : mMapLevels;
  u.shape = glm::vec4(layout.grazingLevels, static_cast<float>(mMapLevels), static_cast<float>(readLevels), 0.0f);
  mBlock.upload(u);
  ++mFrame;
  mStats = {};
  mStats.poolPages = layout.poolPages;
  mStats.levels = levels;
}

ShaderDefines VirtualPages::defines() const {
  ShaderDefines d;
  d.set("PN_VIRTUAL_PAGES");
  d.set("PN_PAGE_SIZE", mLayout.pageSize);
  d.set("PN_PAGES_PER_SIDE", mLayout.pagesPerSide());
  d.set("PN_POOL_TILES_PER_SIDE", mTilesPerSide);
  return d;
}

void VirtualPages::bind() const {
  mBlock.bindBase(GL_UNIFORM_BUFFER, PN_UBO_PAGES);
  mPageTable.bindUnit(PN_TEX_PAGE_TABLE);
}

void VirtualPages::invalidateUnder(const Aabb& world) {
  if (world.empty()) return;
  const std::vector<glm::dvec4> boxes = cullRects(std::span(&world, 1));
  for (Tile& t : mTiles) {
    if (t.page == 0) continue;
    int level;
    int64_t x, y;
    unpackPage(t.page, level, x, y);
    const glm::dvec4 r = pageRect(level, x, y), box = boxes[static_cast<size_t>(mapOf(level))];
    if (r.x > box.z || r.z < box.x || r.y > box.w || r.w < box.y) continue;
    if (mKeepStatic) t.dynamicStale = true;
    else t.valid = false;
  }
}

int VirtualPages::takeTile(uint64_t page) {
  // A free tile, else the one needed least recently, but never one this frame needs.
  int best = -1;
  for (int i = 0; i < static_cast<int>(mTiles.size()); ++i) {
    const Tile& t = mTiles[static_cast<size_t>(i)];
    if (t.page == 0) {
      best = i;
      break;
    }
    if (t.lastNeeded < mFrame && (best < 0 || t.lastNeeded < mTiles[static_cast<size_t>(best)].lastNeeded)) best = i;
  }
  if (best < 0) return -1;
  Tile& t = mTiles[static_cast<size_t>(best)];
  if (t.page != 0) mTileOf.erase(t.page);
  t = {};
  t.page = page;
  mTileOf[page] = best;
  return best;
}

void VirtualPages::mark(FrameContext& frame) {
  // Dynamic casters that moved (or came or went) since the last frame: the pages under where they
  // were and where they are now must be drawn again.
  std::vector<CasterSet::Placement> now = frame.casters().placements();
  const bool sameSet = now.size() == mPlacements.size();
  for (size_t i = 0; i < std::max(now.size(), mPlacements.size()); ++i) {
    const CasterSet::Placement* a = i < mPlacements.size() ? &mPlacements[i] : nullptr;
    const CasterSet::Placement* b = i < now.size() ? &now[i] : nullptr;
    if (sameSet && a->key == b->key) continue;
    if (a && a->dynamic) invalidateUnder(a->bounds);
    if (b && b->dynamic) invalidateUnder(b->bounds);
  }
  mPlacements = std::move(now);

  const uint32_t zero = 0;
  glClearNamedBufferData(mFlags.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glClearNamedBufferSubData(mList.id(), GL_R32UI, 0, sizeof(uint32_t), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  bind();
  mFlags.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_PAGE_FLAGS);
  mList.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_PAGE_LIST);
  const gl::Program& program = frame.screenProgram("passes/virtual_pages.comp.glsl", frame.params());
  FrameContext::dispatch2D(program, frame.screen().x, frame.screen().y, PN_SCREEN_GROUP);
  uint32_t count = 0;
  mList.download(&count, sizeof(count));
  std::vector<uint32_t> list(count);
  if (count > 0) mList.download(list.data(), count * sizeof(uint32_t), sizeof(uint32_t));

  // Coarsest level first: when the pool cannot hold every needed page, the pages left out are
  // the finest, and a read there finds the chain of coarser pages each pixel marked (a coarse
  // page left out instead would leave its points with nothing to read but the far plane). Within
  // a level (of every face) the order is the page's index, so a frame's plan does not hang on the
  // marking's order.
  const int pages = mLayout.pagesPerSide();
  const auto levelOf = [&](uint32_t index) { return static_cast<int>(index / static_cast<uint32_t>(pages * pages)) % mMapLevels; };
  std::sort(list.begin(), list.end(), [&](uint32_t a, uint32_t b) { return levelOf(a) != levelOf(b) ? levelOf(a) > levelOf(b) : a > b; });
  mDraws.clear();
  mStats.needed = static_cast<int>(count);
  for (const uint32_t index : list) {
    const int level = static_cast<int>(index / static_cast<uint32_t>(pages * pages));
    const int y = static_cast<int>(index / static_cast<uint32_t>(pages)) % pages, x = static_cast<int>(index % static_cast<uint32_t>(pages));
    const glm::i64vec2 origin = mLevelOrigin[static_cast<size_t>(level)];
    const uint64_t page = packPage(level, origin.x + x, origin.y + y);
    auto it = mTileOf.find(page);
    const int tile = it != mTileOf.end() ? it->second : takeTile(page);
    if (tile < 0) {
      ++mStats.missing;
      continue;
    }
    Tile& t = mTiles[static_cast<size_t>(tile)];
    t.lastNeeded = mFrame;
    if (!t.valid) mDraws.push_back({tile, true});
    else if (t.dynamicStale) mDraws.push_back({tile, false});
  }
}

void VirtualPages::render(FrameContext& frame, ShadowMapArray& pool, GLuint opaqueProgram, GLuint maskedProgram,
                          const CasterSet& casters, uint64_t passKey) {
  // A new pass (programs, static casters) or new pool storage: this frame's pages are drawn anew, the others dropped.
  Hasher h;
  h.value(passKey);
  h.value(pool.depth().id());
  if (const uint64_t key = h.digest(); key != mPassKey) {
    mPassKey = key;
    mDraws.clear();
    for (size_t i = 0; i < mTiles.size(); ++i) {
      Tile& t = mTiles[i];
      if (t.page == 0) continue;
      if (t.lastNeeded == mFrame) {
        t.valid = false;
        mDraws.push_back({static_cast<int>(i), true});
      } else {
        mTileOf.erase(t.page);
        t = {};
      }
    }
  }
  if (mKeepStatic && !mStaticCopy)
    mStaticCopy = gl::Texture("virtual pages' static casters", {GL_TEXTURE_2D_ARRAY, pool.depth().desc().format, pool.size(), pool.size(),
                                                                pool.layers(), 1});
  if (!mKeepStatic) mStaticCopy = {};

  // Each caster's rectangle in the pages' space (cullRect): a page draws the casters over it alone.
  std::vector<Aabb> bounds;
  bounds.reserve(mPlacements.size());
  for (const CasterSet::Placement& p : mPlacements) bounds.push_back(p.bounds);
  const std::vector<glm::dvec4> rects = cullRects(bounds);  // map after map
  mCasterMask.assign(mPlacements.size(), 0);
  const int ps = mLayout.pageSize, pages = mLayout.pagesPerSide(), perLayer = mTilesPerSide * mTilesPerSide;
  const float clearDepth = 1.0f;
  mDrawnPages.clear();
  glEnable(GL_SCISSOR_TEST);
  for (const Draw& d : mDraws) {
    Tile& t = mTiles[static_cast<size_t>(d.tile)];
    int level;
    int64_t gx, gy;
    unpackPage(t.page, level, gx, gy);
    const glm::i64vec2 origin = mLevelOrigin[static_cast<size_t>(level)];
    const int lx = static_cast<int>(gx - origin.x), ly = static_cast<int>(gy - origin.y);
    mDrawnPages.emplace_back(level, lx, ly);
    const glm::dvec4 r = pageRect(level, gx, gy);
    const glm::dvec4* mapRects = rects.data() + static_cast<size_t>(mapOf(level)) * bounds.size();
    for (size_t i = 0; i < bounds.size(); ++i)
      mCasterMask[i] = mapRects[i].x <= r.z && mapRects[i].z >= r.x && mapRects[i].y <= r.w && mapRects[i].w >= r.y ? 1 : 0;
    const int layer = d.tile / perLayer, inLayer = d.tile % perLayer;
    const int tx = (inLayer % mTilesPerSide) * ps, ty = (inLayer / mTilesPerSide) * ps;
    gl::Framebuffer& fb = pool.framebuffer(layer);
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    glViewport(tx, ty, ps, ps);
    glScissor(tx, ty, ps, ps);
    // The page's part of the level's clip square, [a, a + 2/P] with a = −1 + 2·lx/P, blown up to [−1, 1].
    const glm::vec4 page(static_cast<float>(pages), static_cast<float>(pages), static_cast<float>(pages - 2 * lx - 1),
                         static_cast<float>(pages - 2 * ly - 1));
    for (const GLuint program : {opaqueProgram, maskedProgram}) {
      glProgramUniform1i(program, PN_LOC_VIEW, level);
      glProgramUniform4fv(program, PN_LOC_PAGE, 1, &page.x);
    }
    if (d.whole) {
      glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &clearDepth);
      if (mKeepStatic) {
        casters.draw(opaqueProgram, maskedProgram, CasterSet::Which::Static, frame.translucentCasters(), mCasterMask);
        glCopyImageSubData(pool.depth().id(), GL_TEXTURE_2D_ARRAY, 0, tx, ty, layer, mStaticCopy.id(), GL_TEXTURE_2D_ARRAY, 0, tx, ty,
                           layer, ps, ps, 1);
        casters.draw(opaqueProgram, maskedProgram, CasterSet::Which::Dynamic, frame.translucentCasters(), mCasterMask);
      } else {
        casters.draw(opaqueProgram, maskedProgram, CasterSet::Which::All, frame.translucentCasters(), mCasterMask);
      }
    } else {
      glCopyImageSubData(mStaticCopy.id(), GL_TEXTURE_2D_ARRAY, 0, tx, ty, layer, pool.depth().id(), GL_TEXTURE_2D_ARRAY, 0, tx, ty,
                         layer, ps, ps, 1);
      casters.draw(opaqueProgram, maskedProgram, CasterSet::Which::Dynamic, frame.translucentCasters(), mCasterMask);
    }
    t.valid = true;
    t.dynamicStale = false;
  }
  glDisable(GL_SCISSOR_TEST);
  mStats.drawn = static_cast<int>(mDraws.size());

  // The page table: every valid page whose square is on its level's grid this frame (pages of
  // earlier frames serve too, until evicted); a page a dynamic caster left stale is left out.
  std::fill(mTable.begin(), mTable.end(), 0u);
  for (size_t i = 0; i < mTiles.size(); ++i) {
    const Tile& t = mTiles[i];
    if (t.page == 0 || !t.valid) continue;
    ++mStats.resident;
    if (t.dynamicStale) continue;
    int level;
    int64_t gx, gy;
    unpackPage(t.page, level, gx, gy);
    const glm::i64vec2 origin = mLevelOrigin[static_cast<size_t>(level)];
    const int64_t lx = gx - origin.x, ly = gy - origin.y;
    if (lx < 0 || ly < 0 || lx >= pages || ly >= pages) continue;
    mTable[(static_cast<size_t>(level) * static_cast<size_t>(pages) + static_cast<size_t>(ly)) * static_cast<size_t>(pages) +
           static_cast<size_t>(lx)] = static_cast<uint32_t>(i) + 1u;
  }
  if (mTable != mUploadedTable) {
    glTextureSubImage3D(mPageTable.id(), 0, 0, 0, 0, pages, pages, mLevels, GL_RED_INTEGER, GL_UNSIGNED_INT, mTable.data());
    mUploadedTable = mTable;
  }
  mStats.poolBytes = static_cast<int64_t>(pool.depth().storageBytes()) + (mStaticCopy ? static_cast<int64_t>(mStaticCopy.storageBytes()) : 0);
}

}  // namespace penumbra
