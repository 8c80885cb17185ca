#pragma once
// Full-screen passes that compute one value per pixel (the visibility pass, the renderer's lit
// pass, the micro-benchmarks' lookup kernels) are the fragment shader of one full-screen
// triangle: rasterised, they cost about a fifth less than dispatched as compute on llvmpipe
// (docs/bench.md, "Full-screen passes drawn, not dispatched"). Compute stays for passes that
// read back what they write (contact shadows, temporal accumulation) and for lists of points.
#include "gl/Objects.h"
#include "shader/ShaderLibrary.h"

#include <glm/glm.hpp>

#include <string_view>

namespace penumbra {

/// Where a full-screen fragment pass draws: a framebuffer over one texture (or one layer of a 2D
/// array) as its colour attachment 0, and the empty vertex array the full-screen triangle is
/// drawn from (passes/fullscreen.vert.glsl makes its vertices from gl_VertexID).
class ScreenTarget {
public:
  ScreenTarget() = default;
  /// `layer` >= 0: that layer of a 2D array texture; otherwise the whole (2D) texture.
  ScreenTarget(std::string_view label, const gl::Texture& texture, int layer = -1);
  explicit operator bool() const { return static_cast<bool>(mFramebuffer); }

  /// How a pass's output meets what the target holds: replaces it, or multiplies it (a factor
  /// applied to what an earlier pass wrote: the translucent casters' tint over V).
  enum class Write { Replace, Multiply };
  /// Runs `program` (a fullScreenProgram) once per pixel of the size × size region at the
  /// target's origin: binds the framebuffer and the viewport, turns the depth test and culling
  /// off and blending off (Multiply: on, destination × source, left off after), draws, and
  /// leaves framebuffer 0 and vertex array 0 bound. Followed by a memory barrier, as a dispatch
  /// is, for what the pass wrote through images (debug outputs).
  void draw(const gl::Program& program, glm::ivec2 size, Write write = Write::Replace) const;

private:
  gl::Framebuffer mFramebuffer;
  gl::VertexArray mVertexArray;
};

/// The program of a full-screen pass: `pass` (its fragment sources and defines) with the
/// full-screen triangle's vertex shader.
ProgramDesc fullScreenProgram(ProgramDesc pass);

}  // namespace penumbra
