#include "frame/SatBuilder.h"

#include "shader/ShaderLibrary.h"
#include "shared/Bindings.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <cstdint>
#include <limits>

namespace penumbra {
namespace {

// Work-group shape (sat_scan.comp.glsl). Bands of 64 rows: the carries cost 4 · 16 B per pair per
// 64 texels (1 B/texel) and a 2048² map still gives 32 groups per view. 64 threads of 8 columns
// (chunks of 512 columns), blocks of 4 rows for one moment pair (2 for two). On llvmpipe (8-wide
// SIMD, a group's lanes switched at each barrier, storage-buffer and shared-memory accesses a loop
// over the lanes, a block's partial sums kept in per-lane arrays in memory) 8 columns halve step
// (b), a serial walk over one row's segment totals per block: for a 2048² (z, z²) map the build
// went from 1.86-1.90x a copy (CPU time, 4 columns, 32-row bands) to 1.57-1.61x (8 columns, 64-row
// bands, (b)'s buffers doubled so a block needs 2 barriers, not 3); 4 moments 3.7x to 3.0x the RG32F
// copy. 16 columns, 32 or 128 threads, 8-row blocks were slower; 128-row bands 3 % faster but half
// the groups. Earlier, with 4 columns: 4-row blocks 1.5–1.9× a copy, 8 rows 1.5–2.1×, 16 rows
// 1.9–2.3× (wall clock, 5 processes each).
struct ScanShape {
  int band, pairRows, threads, perThread;  // pairRows: block rows · moment pairs
  constexpr int rows(int pairs) const { return pairRows / pairs; }
  // (b)'s two buffers of segment totals and the row carries
  constexpr int sharedBytes(int pairs) const { return pairs * (2 * rows(pairs) * threads + band) * 16; }
};
constexpr ScanShape kScanShape{64, 4, 64, 8};
constexpr int kMinSharedBytes = 32768;  // GL_MAX_COMPUTE_SHARED_MEMORY_SIZE's required minimum
static_assert(kScanShape.band % kScanShape.rows(1) == 0 && kScanShape.band % kScanShape.rows(2) == 0 &&
              kScanShape.rows(1) <= kScanShape.threads);
static_assert(kScanShape.band % 2 == 0 && kScanShape.rows(2) % 2 == 0 && kScanShape.perThread % 2 == 0,
              "the scan reads the map in 2x2 gathers");
static_assert(kScanShape.sharedBytes(1) <= kMinSharedBytes && kScanShape.sharedBytes(2) <= kMinSharedBytes);

enum ScanPass { kBandTotals = 0, kBandCarries = 1, kBandScan = 2 };

// Fixed-point sums (common/sat.glsl) hold size² · 2^31 in 64 bits.
constexpr int kMaxSatSide = 65536;
constexpr size_t kPairBytes = 16;  // two 64-bit sums: one uvec4 of the table or of the carries

const gl::Program& scanProgram(ShaderLibrary& shaders, ScanPass pass, int pairs) {
  ProgramDesc d;
  d.label = fmt::format("sat scan pass {} pairs {}", static_cast<int>(pass), pairs);
  d.compute = {"passes/sat_scan.comp.glsl"};
  d.defines.set("SAT_PASS", static_cast<int>(pass)).set("SAT_PAIRS", pairs).set("SAT_BAND", kScanShape.band)
      .set("SAT_ROWS", kScanShape.rows(pairs)).set("SAT_THREADS", kScanShape.threads).set("SAT_PER_THREAD", kScanShape.perThread);
  return shaders.program(d);
}

GLuint groups(int n, int per) { return static_cast<GLuint>((n + per - 1) / per); }

}  // namespace

void SatBuilder::build(ShaderLibrary& shaders, const gl::Texture& depth, int momentCount) {
  PN_CHECK(momentCount == 2 || momentCount == 4, fmt::format("SatBuilder: {} moments (2 or 4 supported)", momentCount));
  PN_CHECK(depth.desc().target == GL_TEXTURE_2D_ARRAY, "SatBuilder: the depth input must be a 2D array texture");
  const int w = depth.width(), h = depth.height(), views = depth.layers();
  PN_CHECK(w <= kMaxSatSide && h <= kMaxSatSide, fmt::format("SatBuilder: {}x{} exceeds {} per side", w, h, kMaxSatSide));
  const int pairs = momentCount / 2;
  const size_t tableBytes = static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(views * pairs) * kPairBytes;
  // The readers index the table with a 32-bit int (common/sat.glsl's satIndex): say so rather
  // than read the wrong texels. (Drivers may also refuse the memory: GL_OUT_OF_MEMORY, reported by
  // the pass with a hint to use a smaller map.)
  const size_t elements = tableBytes / kPairBytes;
  PN_CHECK(elements <= static_cast<size_t>(std::numeric_limits<int32_t>::max()),
           fmt::format("the summed-area table of {} view(s) of {}x{} texels with {} moments has {} entries, more than "
                       "its 32-bit index reaches; use smaller maps (Technique::mapSize)",
                       views, w, h, momentCount, elements));
  if (!mTable || mTable.size() != tableBytes) mTable = gl::Buffer("summed-area table", tableBytes);
  mPairs = pairs;
  mWidth = w;
  mHeight = h;
  mLayers = views * pairs;

  const int bands = (h + kScanShape.band - 1) / kScanShape.band;
  const size_t carryBytes = static_cast<size_t>(views) * static_cast<size_t>(bands) * static_cast<size_t>(w) *
                            static_cast<size_t>(pairs) * kPairBytes;
  if (!mCarry || mCarry.size() < carryBytes) mCarry = gl::Buffer("summed-area table band carries", carryBytes);

  depth.bindUnit(PN_TEX_FILTER0);
  bindTable();
  mCarry.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
  scanProgram(shaders, kBandTotals, pairs).use();
  glDispatchCompute(groups(w, kScanShape.threads * kScanShape.perThread), static_cast<GLuint>(bands), static_cast<GLuint>(views));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  scanProgram(shaders, kBandCarries, pairs).use();
  glDispatchCompute(groups(w, kScanShape.threads), 1, static_cast<GLuint>(views));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  scanProgram(shaders, kBandScan, pairs).use();
  glDispatchCompute(1, static_cast<GLuint>(bands), static_cast<GLuint>(views));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void SatBuilder::bindTable() const { mTable.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_SAT); }

double SatBuilder::trafficBytesPerTexel(int momentCount, int height) {
  const int bands = (height + kScanShape.band - 1) / kScanShape.band;
  const double pairBytes = static_cast<double>(momentCount / 2) * static_cast<double>(kPairBytes);
  return 2.0 * sizeof(float) + pairBytes + 4.0 * pairBytes * bands / height;
}

}  // namespace penumbra
