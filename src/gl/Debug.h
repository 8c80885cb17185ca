#pragma once
// GL errors and facts about the current context, for any code that holds one (the caller's
// context in an engine, the platform's in Penumbra's tools).
#include <epoxy/gl.h>

#include <string>
#include <string_view>

namespace penumbra::gl {

/// Records GL errors from the driver's debug messages (GL_KHR_debug), synchronously, so that
/// throwIfGlError reports the first one with the driver's own words.
void installDebugMessageCallback();
/// Throws penumbra::Error if the debug callback recorded a GL error (or glGetError reports one)
/// since the last call. The renderer calls it after every pass.
void throwIfGlError(const char* where);

/// glGetString as a string ("" when the driver returns none).
std::string glString(GLenum name);
/// True on software rasterisers (llvmpipe, softpipe), whose timer queries read 0 for real work:
/// time passes there with glFinish and a steady clock instead.
bool isSoftwareRenderer(std::string_view renderer);

}  // namespace penumbra::gl
