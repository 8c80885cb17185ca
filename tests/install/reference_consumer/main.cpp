// A 1 m box on a ground under a sun straight overhead: the reference must see the point under
// the box in shadow (V = 0) and a point in the open lit (V = 1). Exit 0 when it does.
#include <penumbra/Bake.h>
#include <penumbra/Reference.h>
#include <penumbra/Scene.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>

int main() {
  penumbra::sdf::installEmbreeBaker();  // links Penumbra::bake
  penumbra::Scene scene;
  penumbra::addObject(scene, "ground", penumbra::makePlane(20.0f, 20.0f), glm::vec3(0.8f));
  penumbra::addObject(scene, "box", penumbra::makeBox(glm::vec3(1.0f)), glm::vec3(0.8f),
                      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 2.0f, 0.0f)));
  penumbra::Light sun;
  sun.direction = {0.0f, -1.0f, 0.0f};
  scene.lights.push_back(sun);
  penumbra::GBufferData g;
  g.width = 2;
  g.height = 1;
  g.position = {{0.0f, 0.0f, 0.0f, 1.0f}, {5.0f, 0.0f, 5.0f, 1.0f}};
  g.geoNormal = g.normal = {{0.0f, 1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f, 0.0f}};
  g.albedo = {glm::vec4(0.8f), glm::vec4(0.8f)};
  penumbra::ReferenceOptions options;
  options.useCache = false;
  options.progress = false;
  const penumbra::ReferenceResult r = penumbra::ReferenceTracer(scene).trace(g, scene.light(), options);
  std::printf("V under the box %.3f, in the open %.3f\n", r.visibility[0], r.visibility[1]);
  return r.visibility[0] == 0.0f && r.visibility[1] == 1.0f ? 0 : 1;
}
