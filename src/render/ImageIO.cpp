#include <penumbra/Error.h>
#include <penumbra/ImageIO.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <fmt/format.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image.h>
#include <stb_image_write.h>
#pragma GCC diagnostic pop

#include <atomic>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace penumbra {
namespace {

std::atomic<unsigned> gTemporaryCounter{0};

// Unique per process and call: two runs (or threads) writing the same file never share one.
std::filesystem::path temporaryFor(const std::filesystem::path& path) {
  std::filesystem::path tmp = path;
  tmp += fmt::format(".tmp.{}.{}", getpid(), gTemporaryCounter.fetch_add(1));
  return tmp;
}

void commit(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw Error(fmt::format("{}: cannot write ({})", path.string(), ec.message()));
  }
}

void ensureParent(const std::filesystem::path& path) {
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) throw Error(fmt::format("{}: cannot create the folder ({})", path.parent_path().string(), ec.message()));
  }
}

}  // namespace

void writePng(const std::filesystem::path& path, int width, int height, std::span<const uint8_t> rgba) {
  PN_CHECK(rgba.size() == static_cast<size_t>(width) * static_cast<size_t>(height) * 4,
           fmt::format("{}: pixel count does not match {}x{}", path.string(), width, height));
  ensureParent(path);
  const std::filesystem::path tmp = temporaryFor(path);
  if (!stbi_write_png(tmp.c_str(), width, height, 4, rgba.data(), width * 4))
    throw Error(fmt::format("{}: cannot write the PNG", path.string()));
  commit(tmp, path);
}

void writeExr(const std::filesystem::path& path, int width, int height, std::span<const float> values,
              const char* channel) {
  PN_CHECK(values.size() == static_cast<size_t>(width) * static_cast<size_t>(height),
           fmt::format("{}: pixel count does not match {}x{}", path.string(), width, height));
  ensureParent(path);
  const std::filesystem::path tmp = temporaryFor(path);
  try {
    Imf::Header header(width, height);
    header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(tmp.c_str(), header);
    Imf::FrameBuffer fb;
    fb.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(values.data())),
                                  sizeof(float), sizeof(float) * static_cast<size_t>(width)));
    file.setFrameBuffer(fb);
    file.writePixels(height);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw Error(fmt::format("{}: cannot write the EXR ({})", path.string(), e.what()));
  }
  commit(tmp, path);
}

std::vector<uint8_t> readPng(const std::filesystem::path& path, int& width, int& height) {
  int channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &width, &height, &channels, 4);
  if (!data) throw Error(fmt::format("{}: cannot read the PNG ({})", path.string(), stbi_failure_reason()));
  std::vector<uint8_t> out(data, data + static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  stbi_image_free(data);
  return out;
}

std::vector<float> readExr(const std::filesystem::path& path, int& width, int& height) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    width = dw.max.x - dw.min.x + 1;
    height = dw.max.y - dw.min.y + 1;
    const char* channel = file.header().channels().begin().name();
    std::vector<float> out(static_cast<size_t>(width) * static_cast<size_t>(height));
    Imf::FrameBuffer fb;
    fb.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(out.data()) -
                                                  (static_cast<ptrdiff_t>(dw.min.x) + static_cast<ptrdiff_t>(dw.min.y) * width) * 4,
                                  sizeof(float), sizeof(float) * static_cast<size_t>(width)));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return out;
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot read the EXR ({})", path.string(), e.what()));
  }
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
  writeBinaryFile(path, {std::span<const char>(text.data(), text.size())});
}

void writeBinaryFile(const std::filesystem::path& path, std::initializer_list<std::span<const char>> blocks) {
  ensureParent(path);
  const std::filesystem::path tmp = temporaryFor(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    for (std::span<const char> b : blocks) out.write(b.data(), static_cast<std::streamsize>(b.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw Error(fmt::format("{}: cannot write", path.string()));
    }
  }
  commit(tmp, path);
}

}  // namespace penumbra
