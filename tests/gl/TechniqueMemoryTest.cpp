// What a technique keeps on the GPU (Shadows::techniqueMemoryBytes, the bench's shadow_memory_mb):
// counted where GL storage is allocated (gl::MemoryAccount), so a map, a mip chain or a
// summed-area table a filter adds is in the number without the filter listing it.
#include "GlFixture.h"

#include "gl/Objects.h"

#include <penumbra/Shadows.h>

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr int kWidth = 64, kHeight = 48;

size_t memoryAfterOneFrame(const std::string& projection, const std::string& filter, int mapSize, const Params& params = {}) {
  const Scene scene = loadScene("boxes");
  std::unique_ptr<Renderer> r = makeTestRenderer(scene, projection, filter, params, mapSize);
  r->render({.width = kWidth, .height = kHeight, .debugView = 0});
  return r->shadows().techniqueMemoryBytes();
}

}  // namespace

TEST(MemoryAccount, ChargesTexturesAndBuffersMadeInItsScopeUntilTheyAreDestroyed) {
  (void)glContext();
  gl::MemoryAccount account;
  gl::Texture outside("not charged", {GL_TEXTURE_2D, GL_R32F, 16, 16, 1, 1});
  {
    const gl::MemoryAccount::Charge charge(account);
    // 32² + 16² + 8² + 4² + 2² + 1² texels of 4 floats (16 bytes), 3 layers.
    gl::Texture mips("charged mips", {GL_TEXTURE_2D_ARRAY, GL_RGBA32F, 32, 32, 3, 0});
    EXPECT_EQ(mips.storageBytes(), (1024u + 256u + 64u + 16u + 4u + 1u) * 16u * 3u);
    gl::Buffer buffer("charged buffer", 1000);
    EXPECT_EQ(account.bytes(), static_cast<std::int64_t>(mips.storageBytes() + 1000));
    gl::Texture moved = std::move(mips);  // the charge travels with the storage
    EXPECT_EQ(account.bytes(), static_cast<std::int64_t>(moved.storageBytes() + 1000));
  }
  EXPECT_EQ(account.bytes(), 0) << "destroyed objects leave the account";
  gl::Texture after("made after the scope", {GL_TEXTURE_2D, GL_R32F, 16, 16, 1, 1});
  EXPECT_EQ(account.bytes(), 0);
  // A 3D texture's depth halves per level: 8·8·8 + 4·4·4 + 2·2·2 + 1 texels of one float.
  const gl::MemoryAccount::Charge charge(account);
  const gl::Texture volume("volume", {GL_TEXTURE_3D, GL_R32F, 8, 8, 8, 0});
  EXPECT_EQ(volume.storageBytes(), (512u + 64u + 8u + 1u) * 4u);
  EXPECT_EQ(account.bytes(), static_cast<std::int64_t>(volume.storageBytes()));
}

TEST(TechniqueMemory, HardKeepsOneDepthMapPerView) {
  // uniform: one 32-bit depth map; csm: one per cascade.
  EXPECT_EQ(memoryAfterOneFrame("uniform", "hard", 256), 256u * 256u * 4u);
  EXPECT_EQ(memoryAfterOneFrame("csm", "hard", 256, {{"csm.cascades", "3"}}), 3u * 256u * 256u * 4u);
}

TEST(TechniqueMemory, GrowsWithTheMapAndWithWhatTheFilterStores) {
  const size_t hard = memoryAfterOneFrame("uniform", "hard", 512);
  EXPECT_EQ(memoryAfterOneFrame("uniform", "hard", 1024), 4 * hard);
  // vsm adds a two-moment colour map with its mip chain; vssm a summed-area table on top; msm
  // stores four moments.
  const size_t vsm = memoryAfterOneFrame("uniform", "vsm", 512);
  EXPECT_GT(vsm, hard + 512u * 512u * 8u) << "depth + RG32F moments + their mips";
  EXPECT_GT(memoryAfterOneFrame("uniform", "vssm", 512), vsm);
  EXPECT_GT(memoryAfterOneFrame("uniform", "msm", 512, {{"msm.storage", "float32"}}), vsm);
}

TEST(TechniqueMemory, AReplacedTechniqueReleasesItsStorage) {
  const Scene scene = loadScene("boxes");
  std::unique_ptr<Renderer> r = makeTestRenderer(scene, "uniform", "vssm", {}, 256);
  const RenderOptions options{.width = kWidth, .height = kHeight, .debugView = 0};
  r->render(options);
  const size_t vssm = r->shadows().techniqueMemoryBytes();
  r->setTechnique(Technique("uniform", "hard").setMapSize(256));
  // Each light's state is made from the technique at its next frame: until then the old maps stay.
  EXPECT_EQ(r->shadows().techniqueMemoryBytes(), vssm);
  r->render(options);
  EXPECT_EQ(r->shadows().techniqueMemoryBytes(), 256u * 256u * 4u);
  EXPECT_LT(r->shadows().techniqueMemoryBytes(), vssm);
}

// Every light runs its own copy of the technique (its own maps): the count covers them all.
TEST(TechniqueMemory, CountsEveryLightsCopyOfTheTechnique) {
  Scene scene = loadScene("boxes");
  Light second = scene.lights.at(0);
  second.direction = glm::normalize(second.direction + glm::vec3(0.3f, 0.0f, 0.0f));
  second.shadow.mapSize = 128;  // its own size, so its map is told apart from the first light's
  Light unshadowed = second;
  unshadowed.castsShadow = false;  // shines but keeps no map
  scene.lights = {scene.lights.at(0), second, unshadowed};
  std::unique_ptr<Renderer> r = makeTestRenderer(scene, "uniform", "hard", {}, 256);
  r->render({.width = kWidth, .height = kHeight, .debugView = 0});
  EXPECT_EQ(r->shadows().techniqueMemoryBytes(), 256u * 256u * 4u + 128u * 128u * 4u);
}
