// The RAII wrappers of src/gl/Objects.h: gl::liveObjectCount, which the viewer's "no GL object
// growth" check relies on, follows every Sampler (+1 made, −1 destroyed), a move hands the GL
// object over without deleting it twice, and each sampler carries its debug label.
#include "GlFixture.h"

#include "gl/Objects.h"
#include "techniques/filters/PcfFilter.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <utility>

using namespace penumbra;

namespace {
std::string objectLabel(GLenum ns, GLuint id) {
  char text[64] = {};
  GLsizei length = 0;
  glGetObjectLabel(ns, id, sizeof(text), &length, text);
  return std::string(text, static_cast<size_t>(length));
}
}  // namespace

TEST(GlObjects, SamplerIsCountedLabelledAndDeletedOnce) {
  test::glContext();
  const int before = gl::liveObjectCount();
  GLuint id = 0;
  {
    gl::Sampler a("test sampler", {.compare = true});
    id = a.id();
    ASSERT_NE(id, 0u);
    EXPECT_EQ(gl::liveObjectCount(), before + 1);
    EXPECT_TRUE(glIsSampler(id));
    EXPECT_EQ(objectLabel(GL_SAMPLER, id), "test sampler");
    GLint mode = 0;
    glGetSamplerParameteriv(id, GL_TEXTURE_COMPARE_MODE, &mode);
    EXPECT_EQ(mode, GL_COMPARE_REF_TO_TEXTURE);

    // Moved-from: owns nothing; destroying it deletes nothing and counts nothing.
    std::optional<gl::Sampler> b(std::move(a));
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is what is tested
    EXPECT_FALSE(static_cast<bool>(a));
    EXPECT_EQ(b->id(), id);
    EXPECT_EQ(gl::liveObjectCount(), before + 1);
    {
      gl::Sampler c(std::move(*b));
      b.reset();  // the moved-from wrapper's destructor
      EXPECT_TRUE(glIsSampler(id)) << "destroying a moved-from Sampler deleted the object it handed over";
      EXPECT_EQ(gl::liveObjectCount(), before + 1);

      // Move assignment releases the target's own object first.
      gl::Sampler d("test sampler 2", {});
      const GLuint other = d.id();
      EXPECT_EQ(gl::liveObjectCount(), before + 2);
      d = std::move(c);
      EXPECT_FALSE(glIsSampler(other));
      EXPECT_EQ(d.id(), id);
      EXPECT_EQ(gl::liveObjectCount(), before + 1);
    }
    EXPECT_FALSE(glIsSampler(id));
    EXPECT_EQ(gl::liveObjectCount(), before);
  }
  EXPECT_EQ(gl::liveObjectCount(), before) << "the moved-from wrapper went out of scope last";
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(GlObjects, ComparisonSamplerIsCountedFromItsFirstBind) {
  test::glContext();
  const int before = gl::liveObjectCount();
  {
    ComparisonSampler compare;
    EXPECT_EQ(gl::liveObjectCount(), before) << "made lazily: filters exist without a GL context";
    compare.bind(0);
    compare.bind(0);
    EXPECT_EQ(gl::liveObjectCount(), before + 1);
    ComparisonSampler::unbind(0);
  }
  EXPECT_EQ(gl::liveObjectCount(), before);
}
