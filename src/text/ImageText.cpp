#include "text/ImageText.h"

#include <penumbra/Error.h>

#include <algorithm>
#include <cmath>
#include <vector>

// stb_truetype's implementation, private to this file (Dear ImGui compiles its own copy static too).
#define STBTT_STATIC
#define STB_TRUETYPE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wcast-qual"
#endif
#include <stb_truetype.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace penumbra::text {
namespace {

// Decodes one UTF-8 sequence at text[i] and advances i; invalid bytes read as U+FFFD.
int nextCodepoint(std::string_view text, size_t& i) {
  constexpr int kReplacement = 0xFFFD;
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i++);
  if (c < 0x80) return c;
  const int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : -1;
  if (extra < 0 || i + static_cast<size_t>(extra) > text.size()) return kReplacement;
  int cp = c & (0x3F >> extra);
  for (int k = 0; k < extra; ++k) {
    const unsigned char b = byte(i);
    if ((b & 0xC0) != 0x80) return kReplacement;
    cp = (cp << 6) | (b & 0x3F);
    ++i;
  }
  return cp;
}

uint8_t blend(uint8_t dst, uint8_t src, int coverage) {
  return static_cast<uint8_t>((dst * (255 - coverage) + src * coverage + 127) / 255);
}

}  // namespace

std::vector<int> utf8Codepoints(std::string_view utf8) {
  std::vector<int> out;
  for (size_t i = 0; i < utf8.size();) out.push_back(nextCodepoint(utf8, i));
  return out;
}

struct TextPainter::Font {
  stbtt_fontinfo info{};
  float scale = 1.0f;
  int ascent = 0, descent = 0;
};

TextPainter::TextPainter(float pixelHeight) : mFont(std::make_unique<Font>()) {
  const std::span<const unsigned char> font = embeddedFont();
  PN_CHECK(stbtt_InitFont(&mFont->info, font.data(), stbtt_GetFontOffsetForIndex(font.data(), 0)) != 0,
           "the embedded font could not be read");
  mFont->scale = stbtt_ScaleForPixelHeight(&mFont->info, pixelHeight);
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&mFont->info, &ascent, &descent, &gap);
  mFont->ascent = static_cast<int>(std::ceil(static_cast<float>(ascent) * mFont->scale));
  mFont->descent = static_cast<int>(std::ceil(static_cast<float>(-descent) * mFont->scale));
}

TextPainter::~TextPainter() = default;

int TextPainter::ascent() const { return mFont->ascent; }
int TextPainter::descent() const { return mFont->descent; }

int TextPainter::width(std::string_view utf8) const {
  float x = 0.0f;
  int previous = 0;
  for (size_t i = 0; i < utf8.size();) {
    const int cp = nextCodepoint(utf8, i);
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&mFont->info, cp, &advance, &bearing);
    if (previous) x += mFont->scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&mFont->info, previous, cp));
    x += mFont->scale * static_cast<float>(advance);
    previous = cp;
  }
  return static_cast<int>(std::ceil(x));
}

void TextPainter::draw(ColorImage& image, int x0, int baseline, std::string_view utf8, const Rgb& rgb) const {
  float x = static_cast<float>(x0);
  int previous = 0;
  std::vector<unsigned char> coverage;
  for (size_t i = 0; i < utf8.size();) {
    const int cp = nextCodepoint(utf8, i);
    if (previous) x += mFont->scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&mFont->info, previous, cp));
    const float shift = x - std::floor(x);  // sub-pixel start: even spacing at small sizes
    int ix0 = 0, iy0 = 0, ix1 = 0, iy1 = 0;
    stbtt_GetCodepointBitmapBoxSubpixel(&mFont->info, cp, mFont->scale, mFont->scale, shift, 0.0f, &ix0, &iy0, &ix1, &iy1);
    const int w = ix1 - ix0, h = iy1 - iy0;
    if (w > 0 && h > 0) {
      coverage.assign(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
      stbtt_MakeCodepointBitmapSubpixel(&mFont->info, coverage.data(), w, h, w, mFont->scale, mFont->scale, shift, 0.0f, cp);
      const int left = static_cast<int>(std::floor(x)) + ix0, top = baseline + iy0;
      for (int gy = 0; gy < h; ++gy) {
        const int py = top + gy;
        if (py < 0 || py >= image.height) continue;
        for (int gx = 0; gx < w; ++gx) {
          const int px = left + gx;
          const int a = coverage[static_cast<size_t>(gy) * static_cast<size_t>(w) + static_cast<size_t>(gx)];
          if (px < 0 || px >= image.width || a == 0) continue;
          uint8_t* p = &image.rgba[(static_cast<size_t>(py) * static_cast<size_t>(image.width) + static_cast<size_t>(px)) * 4];
          for (int c = 0; c < 3; ++c) p[c] = blend(p[c], rgb[static_cast<size_t>(c)], a);
        }
      }
    }
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&mFont->info, cp, &advance, &bearing);
    x += mFont->scale * static_cast<float>(advance);
    previous = cp;
  }
}

void fillRect(ColorImage& image, int x, int y, int width, int height, const Rgb& rgb) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + width, image.width), y1 = std::min(y + height, image.height);
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) {
      uint8_t* p = &image.rgba[(static_cast<size_t>(py) * static_cast<size_t>(image.width) + static_cast<size_t>(px)) * 4];
      p[0] = rgb[0];
      p[1] = rgb[1];
      p[2] = rgb[2];
      p[3] = 255;
    }
}

void strokeRect(ColorImage& image, int x, int y, int width, int height, int t, const Rgb& rgb) {
  fillRect(image, x, y, width, t, rgb);
  fillRect(image, x, y + height - t, width, t, rgb);
  fillRect(image, x, y, t, height, rgb);
  fillRect(image, x + width - t, y, t, height, rgb);
}

}  // namespace penumbra::text
