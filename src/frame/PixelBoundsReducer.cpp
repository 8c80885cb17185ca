#include "frame/PixelBoundsReducer.h"

#include "shared/Bindings.h"
#include "shared/PixelBounds.h"

#include <penumbra/Error.h>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <limits>
#include <utility>

namespace penumbra {
namespace {

// passes/pixel_bounds.comp.glsl's pixelBoundsKey, inverted.
float keyToFloat(uint32_t key) {
  const uint32_t bits = (key & 0x80000000u) != 0u ? key & 0x7FFFFFFFu : ~key;
  return std::bit_cast<float>(bits);
}

constexpr uint32_t kEmptyMin = 0xFFFFFFFFu, kEmptyMax = 0u;  // as the shader's

}  // namespace

PixelBoundsReducer::PixelBoundsReducer(ShaderLibrary& shaders, ShaderDefines surfaceDefines, glm::ivec2 screen,
                                       const Camera& camera, PassTimer& timer, std::function<void()> bind,
                                       std::function<void()> unbind)
    : mShaders(shaders), mSurfaceDefines(std::move(surfaceDefines)), mScreen(screen), mViewFromWorld(camera.viewFromWorld()), mTimer(timer),
      mBind(std::move(bind)), mUnbind(std::move(unbind)) {}

std::vector<Aabb> PixelBoundsReducer::sliceBounds(const glm::mat4& spaceFromWorld, std::span<const float> sliceNearM,
                                                  std::span<const float> sliceFarM) {
  const size_t slices = sliceNearM.size();
  PN_CHECK(slices >= 1 && slices <= PN_PIXEL_BOUNDS_SLICES && sliceFarM.size() == slices,
           fmt::format("PixelBounds::sliceBounds: {} near and {} far depths (1..{} slices)", slices, sliceFarM.size(),
                       PN_PIXEL_BOUNDS_SLICES));
  gpu::PixelBoundsUniforms u{};
  u.spaceFromWorld = spaceFromWorld;
  for (size_t i = 0; i < slices; ++i) {
    u.sliceNear[i / 4][static_cast<int>(i % 4)] = sliceNearM[i];
    u.sliceFar[i / 4][static_cast<int>(i % 4)] = sliceFarM[i];
  }
  u.info = glm::ivec4(static_cast<int>(slices), 0, 0, 0);
  const gl::Buffer block("pixel bounds block", sizeof u, &u);
  std::vector<uint32_t> keys(slices * PN_PIXEL_BOUNDS_WORDS);
  for (size_t i = 0; i < slices; ++i)
    for (int w = 0; w < PN_PIXEL_BOUNDS_WORDS; ++w) keys[i * PN_PIXEL_BOUNDS_WORDS + static_cast<size_t>(w)] = w < 3 ? kEmptyMin : kEmptyMax;
  const gl::Buffer out("pixel bounds", keys.size() * sizeof(uint32_t), keys.data());

  ProgramDesc d;
  d.label = "pixel bounds";
  d.compute = {"passes/pixel_bounds.comp.glsl"};
  d.defines = mSurfaceDefines;
  const gl::Program& program = mShaders.program(d);
  const ScopedPass pass(mTimer, "projection");
  mBind();
  block.bindBase(GL_UNIFORM_BUFFER, PN_UBO_FILTER);
  out.bindBase(GL_SHADER_STORAGE_BUFFER, PN_SSBO_AUX);
  FrameContext::dispatch2D(program, mScreen.x, mScreen.y, PN_SCREEN_GROUP);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  out.download(keys.data(), keys.size() * sizeof(uint32_t));
  mUnbind();
  ++mPasses;

  std::vector<Aabb> boxes(slices);
  for (size_t i = 0; i < slices; ++i) {
    const uint32_t* k = &keys[i * PN_PIXEL_BOUNDS_WORDS];
    if (k[0] == kEmptyMin) continue;  // no pixel in this slice
    boxes[i].lo = {keyToFloat(k[0]), keyToFloat(k[1]), keyToFloat(k[2])};
    boxes[i].hi = {keyToFloat(k[3]), keyToFloat(k[4]), keyToFloat(k[5])};
  }
  return boxes;
}

glm::vec2 PixelBoundsReducer::depthRange() {
  if (!mDepthRange) {
    // The camera's own view space: depth is −z, over one slice that holds every depth.
    const float nearM[] = {0.0f}, farM[] = {std::numeric_limits<float>::max()};
    const Aabb b = sliceBounds(mViewFromWorld, nearM, farM)[0];
    mDepthRange = b.empty() ? glm::vec2(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity())
                            : glm::vec2(-b.hi.z, -b.lo.z);
  }
  return *mDepthRange;
}

}  // namespace penumbra
