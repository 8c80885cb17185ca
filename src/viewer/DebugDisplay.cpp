#include "viewer/DebugDisplay.h"

#include "platform/Context.h"
#include "gl/Debug.h"
#include "shared/Viewer.h"

#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

namespace penumbra::viewer {
namespace {

bool isIntegerFormat(GLenum f) {
  switch (f) {
    case GL_R8UI: case GL_R8I: case GL_R16UI: case GL_R16I: case GL_R32UI: case GL_R32I:
    case GL_RG8UI: case GL_RG8I: case GL_RG16UI: case GL_RG16I: case GL_RG32UI: case GL_RG32I:
    case GL_RGBA8UI: case GL_RGBA8I: case GL_RGBA16UI: case GL_RGBA16I: case GL_RGBA32UI: case GL_RGBA32I:
    case GL_RGB10_A2UI: case GL_STENCIL_INDEX8:
      return true;
    default:
      return false;
  }
}

int sourceKind(GLenum target) {
  return target == GL_TEXTURE_2D_ARRAY ? PN_VIEWER_SOURCE_2D_ARRAY
         : target == GL_TEXTURE_3D     ? PN_VIEWER_SOURCE_3D
                                       : PN_VIEWER_SOURCE_2D;
}

// The largest rectangle of the texture's aspect ratio centred in `rect`.
glm::ivec4 letterbox(const glm::ivec4& rect, int width, int height) {
  const double sx = static_cast<double>(rect.z) / width, sy = static_cast<double>(rect.w) / height;
  const double s = std::min(sx, sy);
  const int w = std::max(1, static_cast<int>(width * s)), h = std::max(1, static_cast<int>(height * s));
  return {rect.x + (rect.z - w) / 2, rect.y + (rect.w - h) / 2, w, h};
}

// Layer grid (layerCells): window pixels between cells, and the colour behind them, darker than
// the view's backdrop so that the cells' edges show.
constexpr int kLayerGapPx = 2;
constexpr float kGridBackdrop[4] = {0.02f, 0.02f, 0.025f, 1.0f};

}  // namespace

std::vector<glm::ivec4> layerCells(const glm::ivec4& rect, int width, int height, int layers) {
  std::vector<glm::ivec4> cells;
  if (layers < 1 || width < 1 || height < 1) return cells;
  // The column count whose cells hold the largest letterboxed layer.
  int bestColumns = 1;
  double bestScale = -1.0;
  for (int columns = 1; columns <= layers; ++columns) {
    const int rows = (layers + columns - 1) / columns;
    const double cellW = static_cast<double>(rect.z - (columns - 1) * kLayerGapPx) / columns;
    const double cellH = static_cast<double>(rect.w - (rows - 1) * kLayerGapPx) / rows;
    const double scale = std::min(cellW / width, cellH / height);
    if (scale > bestScale) {
      bestScale = scale;
      bestColumns = columns;
    }
  }
  const int columns = bestColumns, rows = (layers + columns - 1) / columns;
  const int cellW = std::max(1, (rect.z - (columns - 1) * kLayerGapPx) / columns);
  const int cellH = std::max(1, (rect.w - (rows - 1) * kLayerGapPx) / rows);
  // The grid centred in rect; row 0 at the top (window y grows upward).
  const int gridW = columns * cellW + (columns - 1) * kLayerGapPx, gridH = rows * cellH + (rows - 1) * kLayerGapPx;
  const int x0 = rect.x + (rect.z - gridW) / 2, top = rect.y + (rect.w + gridH) / 2;
  for (int i = 0; i < layers; ++i) {
    const int column = i % columns, row = i / columns;
    const glm::ivec4 cell{x0 + column * (cellW + kLayerGapPx), top - (row + 1) * cellH - row * kLayerGapPx, cellW, cellH};
    cells.push_back(letterbox(cell, width, height));
  }
  return cells;
}

std::string displayProblem(const gl::Texture& t) {
  if (!t) return "not created yet (render a frame first)";
  const GLenum target = t.desc().target;
  if (target != GL_TEXTURE_2D && target != GL_TEXTURE_2D_ARRAY && target != GL_TEXTURE_3D)
    return "only 2D, 2D array and 3D textures can be shown";
  if (isIntegerFormat(t.desc().format)) return "integer textures cannot be shown";
  return {};
}

DebugDisplay::DebugDisplay(ShaderLibrary& shaders)
    : mShaders(shaders), mBlock("viewer display block", sizeof(gpu::ViewerDisplayUniforms)),
      mRange("viewer display range", 2 * sizeof(uint32_t)), mVao("viewer fullscreen"),
      mSampler("viewer display sampler", {.minFilter = GL_NEAREST_MIPMAP_NEAREST, .magFilter = GL_NEAREST}) {}

glm::vec2 DebugDisplay::draw(const gl::Texture& texture, DisplaySettings s, const glm::ivec4& area, const glm::ivec4* clip) {
  const std::string problem = displayProblem(texture);
  PN_CHECK(problem.empty(), problem);
  if (area.z <= 0 || area.w <= 0) return {s.lo, s.hi};
  const gl::TextureDesc& d = texture.desc();
  const int levels = std::max(d.levels, 1);
  s.level = std::clamp(s.level, 0, levels - 1);
  const int layers = d.target == GL_TEXTURE_2D ? 1 : std::max(1, d.depth >> (d.target == GL_TEXTURE_3D ? s.level : 0));
  s.layer = std::clamp(s.layer, 0, layers - 1);
  s.channel = std::clamp(s.channel, 0, DisplaySettings::kChannelRgb);
  const int width = std::max(1, d.width >> s.level), height = std::max(1, d.height >> s.level);
  // What is drawn where: one layer letterboxed in the area, or every layer in a grid.
  std::vector<std::pair<int, glm::ivec4>> parts;
  const bool grid = s.allLayers && d.target == GL_TEXTURE_2D_ARRAY && layers > 1;
  if (grid) {
    const std::vector<glm::ivec4> cells = layerCells(area, width, height, layers);
    for (int i = 0; i < layers; ++i) parts.emplace_back(i, cells[static_cast<size_t>(i)]);
  } else {
    parts.emplace_back(s.layer, letterbox(area, width, height));
  }

  gpu::ViewerDisplayUniforms u{};
  u.mode = glm::ivec4(s.autoRange ? 1 : 0, s.noData ? 1 : 0, 0, 0);
  u.range = glm::vec4(s.lo, s.hi, s.noData.value_or(0.0f), 0.0f);
  auto upload = [&](int layer, const glm::ivec4& rect) {
    u.source = glm::ivec4(layer, s.level, s.channel, s.turbo ? PN_VIEWER_MAP_TURBO : PN_VIEWER_MAP_GREY);
    u.rect = rect;
    mBlock.upload(u);
  };
  mBlock.bindBase(GL_UNIFORM_BUFFER, PN_VIEWER_UBO_DISPLAY);
  mRange.bindBase(GL_SHADER_STORAGE_BUFFER, PN_VIEWER_SSBO_RANGE);
  texture.bindUnit(PN_VIEWER_TEX_SOURCE);
  mSampler.bindUnit(PN_VIEWER_TEX_SOURCE);

  ShaderDefines defines;
  defines.set("PN_VIEWER_SOURCE", sourceKind(d.target));
  if (s.autoRange) {  // one range over every part shown
    const uint32_t init[2] = {std::numeric_limits<uint32_t>::max(), 0u};
    mRange.upload(init, sizeof(init));
    ProgramDesc range;
    range.label = "viewer range";
    range.compute = {"passes/viewer_range.comp.glsl"};
    range.defines = defines;
    const gl::Program& p = mShaders.program(range);
    p.use();
    for (const auto& [layer, rect] : parts) {
      upload(layer, rect);
      glDispatchCompute(static_cast<GLuint>((rect.z + PN_VIEWER_GROUP - 1) / PN_VIEWER_GROUP),
                        static_cast<GLuint>((rect.w + PN_VIEWER_GROUP - 1) / PN_VIEWER_GROUP), 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  ProgramDesc show;
  show.label = "viewer display";
  show.vertex = {"passes/fullscreen.vert.glsl"};
  show.fragment = {"passes/viewer_display.frag.glsl"};
  show.defines = defines;
  const gl::Program& p = mShaders.program(show);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  if (grid) {  // the gaps between the cells, inside the clip when there is one
    glm::ivec4 box = area;
    if (clip) {
      const glm::ivec2 lo = glm::max(glm::ivec2(area.x, area.y), glm::ivec2(clip->x, clip->y));
      const glm::ivec2 hi = glm::min(glm::ivec2(area.x + area.z, area.y + area.w), glm::ivec2(clip->x + clip->z, clip->y + clip->w));
      box = glm::ivec4(lo, glm::max(hi - lo, glm::ivec2(0)));
    }
    glEnable(GL_SCISSOR_TEST);
    glScissor(box.x, box.y, box.z, box.w);
    glClearBufferfv(GL_COLOR, 0, kGridBackdrop);
  }
  glDisable(GL_SCISSOR_TEST);
  if (clip) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(clip->x, clip->y, clip->z, clip->w);
  }
  p.use();
  glBindVertexArray(mVao.id());
  for (const auto& [layer, rect] : parts) {
    upload(layer, rect);
    glViewport(rect.x, rect.y, rect.z, rect.w);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
  gl::Sampler::unbindUnit(PN_VIEWER_TEX_SOURCE);
  gl::throwIfGlError("the viewer's display pass");

  if (!s.autoRange) return {s.lo, s.hi};
  uint32_t encoded[2] = {0, 0};
  mRange.download(encoded, sizeof(encoded));
  auto decode = [](uint32_t e) {
    return std::bit_cast<float>((e & 0x80000000u) ? (e & 0x7FFFFFFFu) : ~e);
  };
  if (encoded[0] > encoded[1]) return {0.0f, 0.0f};  // no finite value was shown
  return {decode(encoded[0]), decode(encoded[1])};
}

ColorImage readWindow(const glm::ivec4& rect) {
  ColorImage img;
  img.width = rect.z;
  img.height = rect.w;
  std::vector<uint8_t> raw(static_cast<size_t>(rect.z) * static_cast<size_t>(rect.w) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(rect.x, rect.y, rect.z, rect.w, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  for (size_t i = 3; i < raw.size(); i += 4) raw[i] = 255;  // the window's alpha is not part of the picture
  img.rgba = flipRows<uint8_t>(raw, rect.z, rect.w, 4);
  gl::throwIfGlError("reading the window back");
  return img;
}

}  // namespace penumbra::viewer
