// The bytes of DejaVu Sans (fonts-dejavu-core), included at build time (the file CMake found:
// PENUMBRA_FONT_FILE), so the pictures' text and the viewer's labels need no font at run time.
#include "text/ImageText.h"

#ifndef PENUMBRA_FONT_FILE
#error "PENUMBRA_FONT_FILE (the path of DejaVuSans.ttf) is set by CMakeLists.txt"
#endif

// The assembler copies the file into read-only data between two symbols.
__asm__(".section .rodata\n"
        ".balign 16\n"
        ".globl penumbra_font_begin\n"
        "penumbra_font_begin:\n"
        ".incbin \"" PENUMBRA_FONT_FILE "\"\n"
        ".globl penumbra_font_end\n"
        "penumbra_font_end:\n"
        ".previous\n");

extern "C" const unsigned char penumbra_font_begin[];
extern "C" const unsigned char penumbra_font_end[];

namespace penumbra::text {

std::span<const unsigned char> embeddedFont() {
  return {penumbra_font_begin, static_cast<size_t>(penumbra_font_end - penumbra_font_begin)};
}

}  // namespace penumbra::text
