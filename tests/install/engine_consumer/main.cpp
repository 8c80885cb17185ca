// Engine code as engines write it, built against the installed package (install_test.sh): glm's
// .r/.g/.b and .s/.t names next to Penumbra's header (they compile only when nothing Penumbra
// pushes onto its users, a compile definition such as GLM_FORCE_XYZW_ONLY, takes them away), and
// docs/embedding.md's minimal integration, word for word, so that the page's code compiles. It
// prints what it computed and exits 0; it needs no GL context (the integration is not called).
#include <penumbra/Shadows.h>
#include <penumbra/ShadowsDebug.h>  // the tools' header compiles from the package too

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

struct Vertex {
  glm::vec3 position, normal;
};
struct Mesh {
  uint32_t first = 0, count = 0;
  int32_t base = 0;
  glm::mat4 model{1.0f};
  penumbra::Aabb bounds;
};

// docs/embedding.md, "The calls": the minimal integration.
[[maybe_unused]] void minimalIntegration(uint32_t vbo, uint32_t ibo, const std::vector<Mesh>& meshes, const glm::mat4& view,
                                         const glm::mat4& proj, int w, int h, uint32_t depthTexture,
                                         const std::vector<penumbra::Light>& lights) {
  penumbra::Shadows shadows;                                   // once: your GL 4.5 context is current
  shadows.setTechnique(penumbra::Technique("csm", "pcss", {{"pcss.blockerSamples", "16"}}));  // ids and keys: penumbra list

  std::vector<penumbra::CasterMesh> casters;                   // once, or every frame when things move
  for (const Mesh& m : meshes)
    casters.push_back({.vertexBuffer = vbo, .stride = sizeof(Vertex), .positionOffset = offsetof(Vertex, position),
                       .indexBuffer = ibo, .indexType = penumbra::IndexType::UInt16, .firstIndex = m.first,
                       .count = m.count, .baseVertex = m.base, .worldFromObject = m.model, .objectBounds = m.bounds});
  shadows.setCasters(casters);                                 // receivers: measured from your depth

  shadows.render({.camera = penumbra::ShadowCamera::fromMatrices(view, proj, penumbra::DepthConvention::ZeroToOne),
                  .surfaces = {.width = w, .height = h, .depth = depthTexture},   // every frame, after your depth pass
                  .lights = lights});                          // a span of penumbra::Light
  glBindTextureUnit(0, shadows.visibilityArrayTexture());      // your lit pass: texelFetch(s, ivec3(xy, i), 0), 1 = lit
}

}  // namespace

int main() {
  penumbra::Light sun;
  sun.color = glm::vec3(1.0f, 0.9f, 0.8f);
  const glm::vec3 tint(sun.color.r * 0.5f, sun.color.g, sun.color.b);
  glm::vec2 uv(0.25f, 0.75f);
  uv.s += uv.t;
  glm::vec4 rgba(tint, 1.0f);
  rgba.a = uv.s;
  std::printf("tint %.2f %.2f %.2f, uv.s %.2f, alpha %.2f\n", tint.r, tint.g, tint.b, uv.s, rgba.a);
  return rgba.a == 1.0f ? 0 : 1;
}
