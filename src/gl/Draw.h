#pragma once
// Drawing a mesh's triangles in submissions the driver can hold.
#include <epoxy/gl.h>

#include <cstddef>
#include <functional>
#include <optional>

namespace penumbra::gl {

/// How many triangles one submission holds before the driver is flushed, on this context.
/// A software rasteriser (llvmpipe) bins every triangle of a submission in host memory (about
/// 150 B each, kept until it rasterises) and keeps two submissions in flight: one draw of a
/// 500 000-triangle mesh held ~75 MB of bins. Drawn in pieces of kSoftwareTrianglesPerSubmission
/// with a glFlush between them, it holds ~25 MB, and runs no slower (docs/scenes.md#memory).
/// A GPU draws from video memory: 0, one draw a mesh.
inline constexpr size_t kSoftwareTrianglesPerSubmission = 16384;
size_t trianglesPerSubmission();
/// Sets trianglesPerSubmission for this process (0 = never split), or back to what the renderer
/// asks with std::nullopt: for tests that check the pieces draw the same picture.
void setTrianglesPerSubmission(std::optional<size_t> triangles);

/// Called before each piece with the piece's first triangle, counted from the draw's first: what
/// gl_PrimitiveID (which restarts at 0 in every draw) must be offset by.
using BeforePiece = std::function<void(size_t firstTriangle)>;

/// glDrawElementsBaseVertex of GL_TRIANGLES, `count` indices from index `firstIndex` of the bound
/// element buffer, in pieces of trianglesPerSubmission() with a glFlush after each. The pieces
/// draw the triangles in the same order, so the picture is the same bit for bit.
void drawTriangles(GLenum indexType, size_t firstIndex, size_t count, GLint baseVertex,
                   const BeforePiece& beforePiece = {});
/// glDrawArrays of GL_TRIANGLES, in the same pieces.
void drawTriangleArrays(size_t firstVertex, size_t count, const BeforePiece& beforePiece = {});

}  // namespace penumbra::gl
