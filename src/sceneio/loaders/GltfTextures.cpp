// glTF images and texture transforms (GltfTextures.h). Images are decoded only when a material's
// base-colour texture uses them, after a size check (never larger than kMaxImageSide): PNG by
// stb_image (base/ImageIO.cpp holds its implementation), JPEG by libjpeg-turbo's TurboJPEG, which
// is fuzzed upstream without end (Debian's stb_image is not safe on crafted JPEGs:
// base/StbImageFormats.h).
#include "sceneio/loaders/GltfTextures.h"

#include "sceneio/loaders/TinyGltf.h"

#include <fmt/format.h>
#include <stb_image.h>
#include <turbojpeg.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>

namespace penumbra::loaders {
namespace {

/// The format a file's first bytes announce, for the message when stb_image cannot decode it.
std::string formatName(const std::vector<unsigned char>& b, const std::string& mimeType) {
  auto starts = [&](std::string_view magic, size_t at = 0) {
    return b.size() >= at + magic.size() && std::memcmp(b.data() + at, magic.data(), magic.size()) == 0;
  };
  if (starts("RIFF") && starts("WEBP", 8)) return "WebP";
  if (starts("\xABKTX 20\xBB")) return "KTX2 (Basis Universal)";
  if (starts("DDS ")) return "DDS";
  if (starts("GIF8")) return "GIF";
  if (starts("BM")) return "BMP";
  if (starts("\x89PNG")) return "PNG";
  if (starts("\xFF\xD8\xFF")) return "JPEG";
  return mimeType.empty() ? "data" : mimeType;
}

bool isJpeg(const std::vector<unsigned char>& b) { return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF; }

/// Width and height from the file's header, before anything is decoded; false if it is no PNG or
/// JPEG the decoders accept.
bool readSize(const std::vector<unsigned char>& bytes, tjhandle jpeg, int& w, int& h) {
  if (isJpeg(bytes)) {
    int subsampling = 0, colorspace = 0;
    return tjDecompressHeader3(jpeg, bytes.data(), bytes.size(), &w, &h, &subsampling, &colorspace) == 0;
  }
  int channels = 0;
  return stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &channels) != 0;
}

}  // namespace

bool keepEncodedImage(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;  // the bytes of the file, not pixels: decodeImage decodes on use
  image->width = image->height = image->component = -1;
  return true;
}

Image decodeImage(const tinygltf::Image& src, int index, const std::string& file, const std::string& field, uint64_t& decodedBytes) {
  const std::string where = fmt::format("{} (images[{}])", field, index);
  if (src.image.empty()) {
    if (src.uri.rfind("data:", 0) == 0) fail(file, where, "its data URI holds no image tinygltf reads (base64 PNG or JPEG)");
    fail(file, where, src.uri.empty() ? std::string("the image has no data") : fmt::format("its file '{}' could not be read", src.uri));
  }
  if (src.image.size() > static_cast<size_t>(INT32_MAX)) fail(file, where, "the image is larger than 2 GiB");
  const std::unique_ptr<void, int (*)(tjhandle)> jpeg(tjInitDecompress(), &tjDestroy);
  if (!jpeg) fail(file, where, "cannot start the JPEG decoder");
  const std::string format = formatName(src.image, src.mimeType);
  int w = 0, h = 0;
  if (!readSize(src.image, jpeg.get(), w, h)) {
    if (format == "PNG") fail(file, where, fmt::format("a broken PNG file ({})", stbi_failure_reason() ? stbi_failure_reason() : "unknown"));
    if (format == "JPEG") fail(file, where, fmt::format("a broken JPEG file ({})", tjGetErrorStr2(jpeg.get())));
    fail(file, where, fmt::format("{} is not an image format Penumbra decodes (PNG, JPEG)", format));
  }
  if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
    fail(file, where, fmt::format("{}x{} texels; each side must be in 1..{}", w, h, kMaxImageSide));
  const uint64_t bytes = 4ull * static_cast<uint64_t>(w) * static_cast<uint64_t>(h);
  if (decodedBytes + bytes > kMaxImageBytes) fail(file, where, fmt::format("decoded images would take more than {} bytes", kMaxImageBytes));
  Image im;
  im.width = w;
  im.height = h;
  if (isJpeg(src.image)) {
    im.rgba.resize(bytes);
    // A corrupt stretch of data is a warning, as browsers show such files; at most 500
    // progressive scans (TJFLAG_LIMITSCANS: a crafted file can hold millions, minutes each).
    const int flags = TJFLAG_ACCURATEDCT | TJFLAG_LIMITSCANS;
    if (tjDecompress2(jpeg.get(), src.image.data(), src.image.size(), im.rgba.data(), w, 0, h, TJPF_RGBA, flags) != 0 &&
        tjGetErrorCode(jpeg.get()) != TJERR_WARNING)
      fail(file, where, fmt::format("cannot decode the JPEG ({})", tjGetErrorStr2(jpeg.get())));
  } else {
    int channels = 0;
    stbi_uc* pixels = stbi_load_from_memory(src.image.data(), static_cast<int>(src.image.size()), &w, &h, &channels, 4);
    if (!pixels) fail(file, where, fmt::format("cannot decode the PNG ({})", stbi_failure_reason() ? stbi_failure_reason() : "unknown"));
    im.rgba.assign(pixels, pixels + bytes);
    stbi_image_free(pixels);
  }
  decodedBytes += bytes;
  return im;
}

UvTransform readTextureTransform(const tinygltf::TextureInfo& info, const std::string& file, const std::string& field) {
  UvTransform t;
  const auto ext = info.extensions.find("KHR_texture_transform");
  if (ext == info.extensions.end()) return t;
  const std::string base = field + ".extensions.KHR_texture_transform";
  const tinygltf::Value& v = ext->second;
  if (!v.IsObject()) fail(file, base, "expected an object");
  auto number = [&](const tinygltf::Value& x, const std::string& key) {
    const double d = x.IsNumber() ? x.GetNumberAsDouble() : NAN;
    if (!std::isfinite(d) || std::abs(d) > kMaxCoordinateM) fail(file, base + "." + key, "expected a finite number");
    return static_cast<float>(d);
  };
  auto pair = [&](const char* key, glm::vec2 def) {
    if (!v.Has(key)) return def;
    const tinygltf::Value& a = v.Get(key);
    if (!a.IsArray() || a.ArrayLen() != 2) fail(file, base + "." + key, "expected an array of 2 numbers");
    return glm::vec2(number(a.Get(0), key), number(a.Get(1), key));
  };
  const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
  const float rotation = v.Has("rotation") ? number(v.Get("rotation"), "rotation") : 0.0f;
  if (v.Has("texCoord")) {
    const tinygltf::Value& c = v.Get("texCoord");
    if (!c.IsInt() || c.GetNumberAsInt() < 0) fail(file, base + ".texCoord", "expected a non-negative integer");
    t.texCoord = c.GetNumberAsInt();
  }
  // "Rotate the UVs counter-clockwise" as seen on the image, whose v runs down: u' = cos·u +
  // sin·v, v' = −sin·u + cos·v, as three.js's glTF loader applies it (the extension's GLSL
  // sample builds the transposed rotation).
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 translate(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);  // column-major, as GLSL
  const glm::mat3 rotate(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  t.matrix = translate * rotate * scaling;
  return t;
}

}  // namespace penumbra::loaders
