#include "gl/Draw.h"

#include <algorithm>
#include <cstdint>

#include "gl/Debug.h"

namespace penumbra::gl {
namespace {

std::optional<size_t> gTrianglesPerSubmission;

size_t indexBytes(GLenum indexType) {
  return indexType == GL_UNSIGNED_SHORT ? 2 : indexType == GL_UNSIGNED_BYTE ? 1 : 4;
}

// Calls draw(first, count) for each piece of `count` vertices, flushing between pieces.
template <class Draw>
void inPieces(size_t first, size_t count, const BeforePiece& beforePiece, Draw&& draw) {
  const size_t piece = trianglesPerSubmission() * 3;
  if (piece == 0 || count <= piece) {
    if (beforePiece) beforePiece(0);
    draw(first, count);
    return;
  }
  for (size_t at = 0; at < count; at += piece) {
    if (beforePiece) beforePiece(at / 3);
    draw(first + at, std::min(piece, count - at));
    glFlush();
  }
}

}  // namespace

size_t trianglesPerSubmission() {
  if (gTrianglesPerSubmission) return *gTrianglesPerSubmission;
  // Every context of a process comes from one driver: asked once, with the first draw's context.
  static const size_t fromRenderer = isSoftwareRenderer(glString(GL_RENDERER)) ? kSoftwareTrianglesPerSubmission : 0;
  return fromRenderer;
}

void setTrianglesPerSubmission(std::optional<size_t> triangles) { gTrianglesPerSubmission = triangles; }

void drawTriangles(GLenum indexType, size_t firstIndex, size_t count, GLint baseVertex, const BeforePiece& beforePiece) {
  inPieces(firstIndex, count, beforePiece, [&](size_t first, size_t n) {
    glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(n), indexType,
                             reinterpret_cast<const void*>(static_cast<uintptr_t>(first * indexBytes(indexType))),
                             baseVertex);
  });
}

void drawTriangleArrays(size_t firstVertex, size_t count, const BeforePiece& beforePiece) {
  inPieces(firstVertex, count, beforePiece, [](size_t first, size_t n) {
    glDrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(n));
  });
}

}  // namespace penumbra::gl
