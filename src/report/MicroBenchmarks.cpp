#include "report/MicroBenchmarks.h"

#include "platform/Context.h"
#include "gl/Debug.h"
#include "gl/Objects.h"
#include "frame/MipBuilder.h"
#include "frame/PassTimer.h"
#include "frame/SatBuilder.h"
#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <memory>

namespace penumbra::report {
namespace {

// One building block: `prepare` makes its textures (untimed) and returns the timed work.
struct MicroBenchmark {
  const char* name;
  const char* baseline;  // the copy of the same texture layout it is compared with
  std::function<std::string(int mapSize)> describe;
  std::function<std::function<void()>(int mapSize)> prepare;
};

gl::Texture filled(const char* label, GLenum target, GLenum format, int size, int levels, GLenum clearFormat,
                   GLenum clearType) {
  gl::Texture t(label, {target, format, size, size, 1, levels});
  const float pattern[4] = {0.5f, 0.25f, 0.0f, 0.0f};  // any value: the cost does not depend on it
  glClearTexImage(t.id(), 0, clearFormat, clearType, pattern);
  return t;
}

// The copy program (passes/texture_copy.comp.glsl) with `defines`, compiled here (untimed) in a
// library of its own that the timed work keeps alive.
struct CopyProgram {
  std::shared_ptr<ShaderLibrary> shaders;
  const gl::Program* program;
};
CopyProgram copyProgram(const char* label, const ShaderDefines& defines) {
  auto shaders = std::make_shared<ShaderLibrary>();
  ProgramDesc d;
  d.label = label;
  d.compute = {"passes/texture_copy.comp.glsl"};
  d.defines = defines;
  const gl::Program& program = shaders->program(d);
  return {shaders, &program};
}

// The compute-shader copy of every level-0 texel of `t` into a twin texture of the same format
// and layers: one load and one store per texel.
std::function<void()> copyOf(std::shared_ptr<const gl::Texture> t) {
  auto twin = std::make_shared<gl::Texture>("micro copy target", t->desc());
  const GLenum format = t->desc().format;
  PN_CHECK(format == GL_RG32F || format == GL_RGBA32F, "micro copy: unsupported format");
  const CopyProgram copy = copyProgram(
      "micro texture copy", ShaderDefines().set("COPY_FORMAT", format == GL_RG32F ? "rg32f" : "rgba32f").set("COPY_BUFFER", 0));
  return [t, twin, copy] {
    const gl::Program& program = *copy.program;
    t->bindImage(PN_IMG_AUX0, GL_READ_ONLY);
    twin->bindImage(PN_IMG_AUX1, GL_WRITE_ONLY);
    program.use();
    constexpr GLuint kGroup = 8;  // local size of texture_copy.comp.glsl
    glDispatchCompute((static_cast<GLuint>(t->width()) + kGroup - 1) / kGroup,
                      (static_cast<GLuint>(t->height()) + kGroup - 1) / kGroup, static_cast<GLuint>(t->layers()));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  };
}

// The same copy of a storage buffer of uvec4 (a summed-area table) into a twin buffer.
std::function<void()> copyOf(std::shared_ptr<const gl::Buffer> b) {
  auto twin = std::make_shared<gl::Buffer>("micro copy target", b->size());
  const CopyProgram copy = copyProgram("micro buffer copy", ShaderDefines().set("COPY_BUFFER", 1));
  return [b, twin, copy] {
    const gl::Program& program = *copy.program;
    b->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
    twin->bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_SAT);
    program.use();
    constexpr size_t kGroup = 64, kElementBytes = 16;  // local size and uvec4 of texture_copy.comp.glsl
    // Rows of kRowGroups groups: a single row is limited to 65535 groups (4 M elements).
    constexpr size_t kRowGroups = 1024;
    const size_t groups = (b->size() / kElementBytes + kGroup - 1) / kGroup;
    glDispatchCompute(static_cast<GLuint>(std::min(groups, kRowGroups)),
                      static_cast<GLuint>((groups + kRowGroups - 1) / kRowGroups), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };
}

// The summed-area table of `moments` depth powers (vssm: 2, msm-soft: 4) of one mapSize² view,
// built from an R32F depth layer, and a plain copy of that very table (a storage buffer, 16 B per
// texel and moment pair).
struct SatFixture {
  ShaderLibrary shaders;
  gl::Texture depth;
  SatBuilder sat;
  SatFixture(int n, int moments)
      : depth(filled("micro sat depth", GL_TEXTURE_2D_ARRAY, GL_R32F, n, 1, GL_RED, GL_FLOAT)) {
    sat.build(shaders, depth, moments);  // also compiles the scan programs
  }
};

MicroBenchmark satBuild(const char* name, const char* baseline, int moments) {
  return {name, baseline,
          [moments](int n) {
            return fmt::format("SatBuilder::build: the summed-area table of {} depth moments of a {}x{} R32F map", moments, n, n);
          },
          [moments](int n) -> std::function<void()> {
            auto f = std::make_shared<SatFixture>(n, moments);
            return [f, moments] { f->sat.build(f->shaders, f->depth, moments); };
          }};
}

MicroBenchmark satCopy(const char* name, int moments) {
  return {name, "",
          [moments](int n) {
            return fmt::format("compute-shader copy of that table ({} moments: {}x{} uvec4 in a storage buffer, {} layer(s))",
                               moments, n, n, moments / 2);
          },
          [moments](int n) -> std::function<void()> {
            auto f = std::make_shared<SatFixture>(n, moments);
            // The table lives in the fixture: share its ownership with the copy.
            return copyOf(std::shared_ptr<const gl::Buffer>(f, &f->sat.table()));
          }};
}

// VSM's mip chain of RG32F moments and the summed-area tables of vssm (2 moments) and msm-soft
// (4 moments), each after a plain copy of the same texture.
const std::vector<MicroBenchmark>& microBenchmarks() {
  static const std::vector<MicroBenchmark> list = {
      {"copy RG32F", "",
       [](int n) { return fmt::format("compute-shader copy of a {0}x{0} RG32F texture (the (z, z²) map of vsm, level 0)", n); },
       [](int n) -> std::function<void()> {
         return copyOf(std::make_shared<gl::Texture>(filled("micro copy source", GL_TEXTURE_2D, GL_RG32F, n, 1, GL_RG, GL_FLOAT)));
       }},
      {"mip chain RG32F", "copy RG32F",
       [](int n) { return fmt::format("MipBuilder::build: the full box-filter chain of a {0}x{0} RG32F texture", n); },
       [](int n) -> std::function<void()> {
         constexpr int kFullChain = 0;
         auto t = std::make_shared<gl::Texture>(filled("micro mip chain", GL_TEXTURE_2D, GL_RG32F, n, kFullChain, GL_RG, GL_FLOAT));
         return [t] { MipBuilder::build(*t); };
       }},
      satCopy("copy SAT table, 2 moments", 2),
      // The yardstick for the SAT: a copy of the (z, z²) map it summarises (RG32F).
      satBuild("SAT build, 2 moments", "copy RG32F", 2),
      satCopy("copy SAT table, 4 moments", 4),
      satBuild("SAT build, 4 moments", "copy SAT table, 4 moments", 4),
  };
  return list;
}

}  // namespace

std::vector<MicroResult> runMicroBenchmarks(int mapSize, int repetitions, bool cpuClock) {
  std::vector<MicroResult> out;
  PassTimer timer(cpuClock);
  for (const MicroBenchmark& m : microBenchmarks()) {
    // A block that fails is recorded with its error and the others still run: the bench's
    // configurations are measured by then, and the report must not be lost with it.
    try {
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
      out.push_back({m.name, m.describe(mapSize), m.baseline, timeStats(ms), repetitions, ""});
    } catch (const Error& e) {
      out.push_back({m.name, m.describe(mapSize), m.baseline, TimeStats{}, 0, e.what()});
    }
  }
  return out;
}

}  // namespace penumbra::report
