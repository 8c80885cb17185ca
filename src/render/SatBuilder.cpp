#include "render/SatBuilder.h"

#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

namespace penumbra {
namespace {

// Work-group shapes (sat_scan.comp.glsl): 8 neighbouring lines per group (adjacent threads read
// adjacent texels in the column pass), 8 threads per line, 32 texels per thread, so a chunk is
// 256 texels and the shared-memory scan takes 6 barriers. 64-thread groups; on llvmpipe, which
// runs a group's threads as 8-wide SIMD coroutines switched at every barrier, one line per
// group with 64 threads was 10x slower (the lanes then walk one row instead of eight).
struct ScanShape {
  int lines, threads, perThread;
};
constexpr ScanShape kScanShape{8, 8, 32};

// Fixed-point sums (common/sat.glsl) hold size² · 2^31 in 64 bits.
constexpr int kMaxSatSide = 65536;

const gl::Program& scanProgram(ShaderLibrary& shaders, int axis, int pairs, const ScanShape& shape) {
  ProgramDesc d;
  d.label = fmt::format("sat scan axis {} pairs {}", axis, pairs);
  d.compute = {"passes/sat_scan.comp.glsl"};
  d.defines.set("SAT_AXIS", axis).set("SAT_PAIRS", pairs).set("SAT_LINES", shape.lines)
      .set("SAT_THREADS", shape.threads).set("SAT_PER_THREAD", shape.perThread);
  return shaders.program(d);
}

}  // namespace

void SatBuilder::build(ShaderLibrary& shaders, const gl::Texture& depth, int momentCount) {
  PN_CHECK(momentCount == 2 || momentCount == 4, fmt::format("SatBuilder: {} moments (2 or 4 supported)", momentCount));
  PN_CHECK(depth.desc().target == GL_TEXTURE_2D_ARRAY, "SatBuilder: the depth input must be a 2D array texture");
  const int w = depth.width(), h = depth.height(), views = depth.layers();
  PN_CHECK(w <= kMaxSatSide && h <= kMaxSatSide, fmt::format("SatBuilder: {}x{} exceeds {} per side", w, h, kMaxSatSide));
  const int pairs = momentCount / 2;
  if (!mTable || mTable.width() != w || mTable.height() != h || mTable.layers() != views * pairs) {
    mTable = gl::Texture("summed-area table", {GL_TEXTURE_2D_ARRAY, GL_RGBA32UI, w, h, views * pairs, 1});
    mTable.setSampling(GL_NEAREST, GL_NEAREST);  // integer textures are only complete unfiltered
  }
  mPairs = pairs;

  depth.bindUnit(PN_TEX_FILTER0);
  mTable.bindImage(PN_IMG_AUX0, GL_READ_WRITE);
  const gl::Program& rows = scanProgram(shaders, 0, pairs, kScanShape);
  rows.use();
  glDispatchCompute(static_cast<GLuint>((h + kScanShape.lines - 1) / kScanShape.lines), 1, static_cast<GLuint>(views));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  const gl::Program& columns = scanProgram(shaders, 1, pairs, kScanShape);
  columns.use();
  glDispatchCompute(static_cast<GLuint>((w + kScanShape.lines - 1) / kScanShape.lines), 1, static_cast<GLuint>(views));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

}  // namespace penumbra
