#include "core/SurfaceBounds.h"

#include "frame/FrameContext.h"
#include "shared/Bindings.h"

#include <array>
#include <bit>
#include <cstring>

namespace penumbra::core {
namespace {

// surface_bounds.glsl's order-preserving encoding of a float, and back.
uint32_t ordered(float f) {
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}
float fromOrdered(uint32_t u) { return std::bit_cast<float>((u & 0x80000000u) != 0 ? u & 0x7fffffffu : ~u); }

}  // namespace

Aabb SurfaceBounds::measure(ShaderLibrary& shaders, glm::ivec2 screen, const ShaderDefines& surfaceDefines) {
  constexpr float kNone = 3.4e38f;  // the empty box the shader starts from
  const uint32_t lo = ordered(kNone), hi = ordered(-kNone);
  const std::array<uint32_t, 6> start = {lo, lo, lo, hi, hi, hi};
  mBounds.upload(start.data(), sizeof(start));
  mBounds.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
  ProgramDesc d;
  d.label = "surface bounds";
  d.compute = {"passes/surface_bounds.glsl"};
  d.defines = surfaceDefines;
  FrameContext::dispatch2D(shaders.program(d), screen.x, screen.y, PN_SCREEN_GROUP);
  std::array<uint32_t, 6> result{};
  mBounds.download(result.data(), sizeof(result));
  Aabb box;
  box.lo = {fromOrdered(result[0]), fromOrdered(result[1]), fromOrdered(result[2])};
  box.hi = {fromOrdered(result[3]), fromOrdered(result[4]), fromOrdered(result[5])};
  return box.lo.x <= box.hi.x ? box : Aabb();
}

}  // namespace penumbra::core
