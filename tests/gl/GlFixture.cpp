#include "GlFixture.h"

#include "bake/SdfBake.h"

#include <memory>

namespace penumbra::test {

gl::HeadlessContext& glContext() {
  static std::unique_ptr<gl::HeadlessContext> context = std::make_unique<gl::HeadlessContext>(gl::ContextOptions{.debug = true});
  return *context;
}

std::unique_ptr<Renderer> makeTestRenderer(const Scene& sceneIn, const std::string& projection,
                                           const std::string& filter, const Params& params, int mapSize) {
  Scene scene = sceneIn;
  Technique technique(projection, filter);
  technique.setMapSize(mapSize);
  applySettings(params, scene, technique);
  glContext();  // made current before the renderer
  auto renderer = std::make_unique<Renderer>();
  renderer->setScene(scene);
  renderer->setTechnique(technique);
  return renderer;
}

void setMapSize(Renderer& renderer, int mapSize) {
  Technique t = renderer.technique();
  t.setMapSize(mapSize);
  renderer.setTechnique(t);
}

RenderResult renderScene(const Scene& scene, const std::string& projection, const std::string& filter,
                         const Params& params, int width, int height, int mapSize) {
  const std::unique_ptr<Renderer> owned = makeTestRenderer(scene, projection, filter, params, mapSize);
  Renderer& renderer = *owned;
  RenderOptions o;
  o.width = width;
  o.height = height;
  renderer.render(o);
  RenderResult r;
  r.visibility = renderer.readVisibility();
  r.gbuffer = renderer.readGBuffer();
  r.frusta = renderer.frusta();
  r.timings = renderer.timings();
  r.width = width;
  r.height = height;
  return r;
}

glm::ivec2 projectToPixel(const Scene& scene, const glm::vec3& ws, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::vec4 c = scene.camera.clipFromView(aspect) * scene.camera.viewFromWorld() * glm::vec4(ws, 1.0f);
  const glm::vec2 ndc = glm::vec2(c) / c.w;
  return glm::ivec2((ndc * 0.5f + 0.5f) * glm::vec2(width, height));
}

}  // namespace penumbra::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  penumbra::sdf::installEmbreeBaker();  // as the CLI does: the sdf filter bakes with Embree
  return RUN_ALL_TESTS();
}
