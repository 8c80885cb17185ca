#pragma once
// Text on images (compare's sheet: titles, legend, metrics), anti-aliased from a TrueType font
// (stb_truetype) embedded in the binary: DejaVu Sans, whose glyphs cover the labels' Greek,
// arrows and maths (λ, Δ, →, ≤, −, ²).
#include <penumbra/Image.h>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace penumbra::text {

/// The embedded font file's bytes (DejaVu Sans, TrueType).
std::span<const unsigned char> embeddedFont();

/// The code points of UTF-8 text; an invalid byte reads as U+FFFD.
std::vector<int> utf8Codepoints(std::string_view utf8);

using Rgb = std::array<uint8_t, 3>;

/// Draws UTF-8 text at one size with the embedded font.
class TextPainter {
public:
  /// `pixelHeight`: from the highest ascender to the lowest descender, in pixels.
  explicit TextPainter(float pixelHeight);
  ~TextPainter();
  TextPainter(const TextPainter&) = delete;
  TextPainter& operator=(const TextPainter&) = delete;

  /// Advance width of the text in pixels.
  int width(std::string_view utf8) const;
  int ascent() const;   ///< pixels above the baseline
  int descent() const;  ///< pixels below the baseline (positive)
  /// Blends the text in `rgb` onto `image` (row 0 = top) with its baseline at y = baseline,
  /// starting at x; glyphs are clipped to the image. A code point the font lacks draws its
  /// "missing glyph" box, as any text renderer would.
  void draw(ColorImage& image, int x, int baseline, std::string_view utf8, const Rgb& rgb) const;

private:
  struct Font;
  std::unique_ptr<Font> mFont;
};

/// Fills a rectangle (clipped to the image).
void fillRect(ColorImage& image, int x, int y, int width, int height, const Rgb& rgb);
/// Draws a rectangle's outline `thickness` pixels wide inside its bounds.
void strokeRect(ColorImage& image, int x, int y, int width, int height, int thickness, const Rgb& rgb);

}  // namespace penumbra::text
