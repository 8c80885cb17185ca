#include "report/MicroBenchmarks.h"

#include "gl/Context.h"
#include "gl/Objects.h"
#include "render/MipBuilder.h"
#include "render/PassTimer.h"

#include <fmt/format.h>

#include <functional>

namespace penumbra::report {
namespace {

// One building block: `prepare` makes its textures (untimed) and returns the timed work.
struct MicroBenchmark {
  const char* name;
  const char* baseline;  // the copy of the same texture layout it is compared with
  std::function<std::string(int mapSize)> describe;
  std::function<std::function<void()>(int mapSize)> prepare;
};

gl::Texture filled(const char* label, GLenum format, int size, int levels, GLenum clearFormat, GLenum clearType) {
  gl::Texture t(label, {GL_TEXTURE_2D, format, size, size, 1, levels});
  const uint32_t pattern[4] = {0x3F000000u, 0x3E800000u, 0u, 0u};  // 0.5, 0.25 as floats; any bits for uints
  glClearTexImage(t.id(), 0, clearFormat, clearType, pattern);
  return t;
}

// A plain copy of a texture in the moment-SAT layout (RGBA32UI: two 64-bit sums per texel) and
// the box-filter mip chain of VSM's RG32F moments, on the same texel count.
const std::vector<MicroBenchmark>& microBenchmarks() {
  static const std::vector<MicroBenchmark> list = {
      {"copy RGBA32UI", "",
       [](int n) { return fmt::format("glCopyImageSubData of a {0}x{0} RGBA32UI texture (a moment SAT's layout, 16 B/texel)", n); },
       [](int n) -> std::function<void()> {
         auto src = std::make_shared<gl::Texture>(filled("micro copy source", GL_RGBA32UI, n, 1, GL_RGBA_INTEGER, GL_UNSIGNED_INT));
         auto dst = std::make_shared<gl::Texture>("micro copy target", gl::TextureDesc{GL_TEXTURE_2D, GL_RGBA32UI, n, n, 1, 1});
         return [src, dst, n] {
           glCopyImageSubData(src->id(), GL_TEXTURE_2D, 0, 0, 0, 0, dst->id(), GL_TEXTURE_2D, 0, 0, 0, 0, n, n, 1);
         };
       }},
      {"copy RG32F", "",
       [](int n) { return fmt::format("glCopyImageSubData of a {0}x{0} RG32F texture (VSM moments, 8 B/texel)", n); },
       [](int n) -> std::function<void()> {
         auto src = std::make_shared<gl::Texture>(filled("micro copy source", GL_RG32F, n, 1, GL_RG, GL_FLOAT));
         auto dst = std::make_shared<gl::Texture>("micro copy target", gl::TextureDesc{GL_TEXTURE_2D, GL_RG32F, n, n, 1, 1});
         return [src, dst, n] {
           glCopyImageSubData(src->id(), GL_TEXTURE_2D, 0, 0, 0, 0, dst->id(), GL_TEXTURE_2D, 0, 0, 0, 0, n, n, 1);
         };
       }},
      {"mip chain RG32F", "copy RG32F",
       [](int n) { return fmt::format("MipBuilder::build: the full box-filter chain of a {0}x{0} RG32F texture", n); },
       [](int n) -> std::function<void()> {
         constexpr int kFullChain = 0;
         auto t = std::make_shared<gl::Texture>(filled("micro mip chain", GL_RG32F, n, kFullChain, GL_RG, GL_FLOAT));
         return [t] { MipBuilder::build(*t); };
       }},
  };
  return list;
}

}  // namespace

std::vector<MicroResult> runMicroBenchmarks(int mapSize, int repetitions, bool cpuClock) {
  std::vector<MicroResult> out;
  PassTimer timer(cpuClock);
  for (const MicroBenchmark& m : microBenchmarks()) {
    const std::function<void()> work = m.prepare(mapSize);
    work();  // untimed: first use of a code path (and of the memory) costs extra
    gl::throwIfGlError(m.name);
    std::vector<double> ms;
    for (int i = 0; i < repetitions; ++i) {
      timer.beginFrame();
      timer.begin(m.name);
      work();
      timer.end();
      ms.push_back(timer.endFrame().total());
    }
    gl::throwIfGlError(m.name);
    out.push_back({m.name, m.describe(mapSize), m.baseline, timeStats(ms), repetitions});
  }
  return out;
}

}  // namespace penumbra::report
