// One-channel float EXR files through OpenEXR: exact values (visibility, depth maps, the
// reference's V) for anyone's tools. Written atomically like every output file.
#include "base/AtomicFile.h"

#include <penumbra/Error.h>
#include <penumbra/Exr.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <fmt/format.h>

namespace penumbra {

void writeExr(const std::filesystem::path& path, int width, int height, std::span<const float> values,
              const char* channel) {
  PN_CHECK(values.size() == static_cast<size_t>(width) * static_cast<size_t>(height),
           fmt::format("{}: pixel count does not match {}x{}", path.string(), width, height));
  AtomicFile file(path);
  try {
    Imf::Header header(width, height);
    header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile exr(file.temporary().c_str(), header);
    Imf::FrameBuffer fb;
    fb.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(values.data())),
                                  sizeof(float), sizeof(float) * static_cast<size_t>(width)));
    exr.setFrameBuffer(fb);
    exr.writePixels(height);
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: cannot write the EXR ({})", path.string(), e.what()));
  }
  file.commit();
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

}  // namespace penumbra
