#include "frame/ScreenTarget.h"

#include <penumbra/Error.h>

#include <string>

namespace penumbra {

ScreenTarget::ScreenTarget(std::string_view label, const gl::Texture& texture, int layer)
    : mFramebuffer(label), mVertexArray(std::string(label) + " (full-screen triangle)") {
  mFramebuffer.attach(GL_COLOR_ATTACHMENT0, texture, 0, layer);
  mFramebuffer.finish(1);
}

void ScreenTarget::draw(const gl::Program& program, glm::ivec2 size, Write write) const {
  PN_ASSERT(mFramebuffer && !program.isCompute());
  glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.id());
  glViewport(0, 0, size.x, size.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  if (write == Write::Multiply) {
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR);  // destination × source, per channel
  }
  program.use();
  glBindVertexArray(mVertexArray.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

ProgramDesc fullScreenProgram(ProgramDesc pass) {
  PN_CHECK(pass.compute.empty() && pass.vertex.empty() && !pass.fragment.empty(),
           "fullScreenProgram: a full-screen pass is its fragment sources");
  pass.vertex = {"passes/fullscreen.vert.glsl"};
  return pass;
}

}  // namespace penumbra
