// Engine code as engines write it: glm's .r/.g/.b and .s/.t names next to Penumbra's headers.
// It compiles only when nothing Penumbra pushes onto its users (a compile definition such as
// GLM_FORCE_XYZW_ONLY) takes those names away; it prints what it computed and exits 0.
#include <penumbra/Shadows.h>

#include <glm/glm.hpp>

#include <cstdio>

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
