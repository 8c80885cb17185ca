#include "bench/MicroBenchmarks.h"

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

// The build of a table and the copy of that table share one fixture (made by whichever is
// prepared first): one table in memory, not two.
using SharedSat = std::shared_ptr<std::shared_ptr<SatFixture>>;
std::shared_ptr<SatFixture> satFixture(const SharedSat& shared, int n, int moments) {
  if (!*shared) *shared = std::make_shared<SatFixture>(n, moments);
  return *shared;
}

MicroItem satBuild(const char* baseline, int n, int moments, bool cpuClock, const SharedSat& shared) {
  std::string name = fmt::format("SAT build, {} moments", moments);
  return {name, fmt::format("SatBuilder::build: the summed-area table of {} depth moments of a {}x{} R32F map", moments, n, n),
          baseline, [=] {
            auto f = satFixture(shared, n, moments);
            return timedWork(cpuClock, name, [f, moments] { f->sat.build(f->shaders, f->depth, moments); });
          }};
}

MicroItem satCopy(int n, int moments, bool cpuClock, const SharedSat& shared) {
  std::string name = fmt::format("copy SAT table, {} moments", moments);
  return {name,
          fmt::format("compute-shader copy of that table ({} moments: {}x{} uvec4 in a storage buffer, {} layer(s))",
                      moments, n, n, moments / 2),
          "", [=] {
            auto f = satFixture(shared, n, moments);
            // The table lives in the fixture: share its ownership with the copy.
            return timedWork(cpuClock, name, copyOf(std::shared_ptr<const gl::Buffer>(f, &f->sat.table())));
          }};
}

}  // namespace

std::function<double()> timedWork(bool cpuClock, std::string name, std::function<void()> work) {
  auto timer = std::make_shared<PassTimer>(cpuClock);
  return [timer, name = std::move(name), work = std::move(work)] {
    timer->beginFrame();
    timer->begin(name);
    work();
    timer->end();
    return timer->endFrame().total();
  };
}

std::vector<MicroResult> runMicroItems(const std::vector<MicroItem>& items, int rounds) {
  struct State {
    std::function<double()> work;
    std::vector<double> ms;
    std::string error;
  };
  std::vector<State> state(items.size());
  // A block that fails is recorded with its error and the others still run: the bench's
  // configurations are measured by then, and the report must not be lost with it.
  auto attempt = [&](size_t i, const std::function<void()>& step) {
    if (!state[i].error.empty()) return;
    try {
      step();
      gl::throwIfGlError(items[i].name.c_str());
    } catch (const std::exception& e) {
      state[i].error = e.what();
      state[i].ms.clear();
    }
  };
  auto runs = [&](size_t i) { return items[i].sameAs.empty(); };
  for (size_t i = 0; i < items.size(); ++i)
    if (runs(i)) attempt(i, [&] { state[i].work = items[i].prepare(); });
  for (size_t i = 0; i < items.size(); ++i)
    if (runs(i)) attempt(i, [&] { state[i].work(); });  // untimed
  for (int r = 0; r < rounds; ++r)
    for (size_t i = 0; i < items.size(); ++i)
      if (runs(i)) attempt(i, [&] { state[i].ms.push_back(state[i].work()); });
  for (size_t i = 0; i < items.size(); ++i) {
    if (runs(i)) continue;
    const auto same = std::find_if(items.begin(), items.end(), [&](const MicroItem& m) { return m.name == items[i].sameAs; });
    if (same == items.end()) {
      state[i].error = fmt::format("no item '{}' to take the times of", items[i].sameAs);
    } else {
      state[i].ms = state[static_cast<size_t>(same - items.begin())].ms;
      state[i].error = state[static_cast<size_t>(same - items.begin())].error;
    }
  }

  std::vector<MicroResult> out;
  for (size_t i = 0; i < items.size(); ++i) {
    const MicroItem& m = items[i];
    const State& s = state[i];
    MicroResult r{m.name, m.description, m.baseline, timeStats(s.ms), s.error.empty() ? rounds : 0, s.error, {}};
    for (size_t b = 0; b < items.size(); ++b) {
      if (m.baseline.empty() || items[b].name != m.baseline || !s.error.empty() || !state[b].error.empty()) continue;
      std::vector<double> ratios;
      for (size_t k = 0; k < s.ms.size() && k < state[b].ms.size(); ++k)
        if (state[b].ms[k] > 0.0) ratios.push_back(s.ms[k] / state[b].ms[k]);
      if (!ratios.empty()) r.ratio = timeStats(ratios);
    }
    out.push_back(std::move(r));
  }
  return out;
}

// VSM's mip chain of RG32F moments and the summed-area tables of vssm (2 moments) and msm-soft
// (4 moments), each with a plain copy of the same texture.
std::vector<MicroResult> runMicroBenchmarks(int n, int repetitions, bool cpuClock) {
  const SharedSat sat2 = std::make_shared<std::shared_ptr<SatFixture>>();
  const SharedSat sat4 = std::make_shared<std::shared_ptr<SatFixture>>();
  const std::vector<MicroItem> items = {
      {"copy RG32F", fmt::format("compute-shader copy of a {0}x{0} RG32F texture (the (z, z²) map of vsm, level 0)", n), "",
       [=] {
         return timedWork(cpuClock, "copy RG32F",
                          copyOf(std::make_shared<gl::Texture>(filled("micro copy source", GL_TEXTURE_2D, GL_RG32F, n, 1, GL_RG, GL_FLOAT))));
       }},
      {"mip chain RG32F", fmt::format("MipBuilder::build: the full box-filter chain of a {0}x{0} RG32F texture", n), "copy RG32F",
       [=] {
         constexpr int kFullChain = 0;
         auto t = std::make_shared<gl::Texture>(filled("micro mip chain", GL_TEXTURE_2D, GL_RG32F, n, kFullChain, GL_RG, GL_FLOAT));
         return timedWork(cpuClock, "mip chain RG32F", [t] { MipBuilder::build(*t); });
       }},
      satCopy(n, 2, cpuClock, sat2),
      // The yardstick for the SAT: a copy of the (z, z²) map it summarises (RG32F).
      satBuild("copy RG32F", n, 2, cpuClock, sat2),
      satCopy(n, 4, cpuClock, sat4),
      satBuild("copy SAT table, 4 moments", n, 4, cpuClock, sat4),
  };
  return runMicroItems(items, repetitions);
}

}  // namespace penumbra::report
