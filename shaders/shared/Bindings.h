#pragma once
// Binding points shared by C++ and GLSL. One name per slot; never a bare number in either.

// Uniform blocks
#define PN_UBO_FRAME 0    // FrameUniforms: camera, light, screen (Frame.h)
#define PN_UBO_SHADOW 1   // ShadowUniforms: the light's shadow views (Shadow.h)
#define PN_UBO_FILTER 2   // the active filter's own block (its shared header)
#define PN_UBO_PAGES 3    // PagesUniforms: a paged projection's level selection (VirtualPages.h)

// Storage blocks
#define PN_SSBO_OBJECTS 0  // ObjectGpu[]: per-object transform and material (Frame.h)
#define PN_SSBO_TEST 1     // GLSL unit tests write their results here
#define PN_SSBO_AUX 2      // free for a pass's own data (the core's surface bounds: passes/surface_bounds.glsl)
#define PN_SSBO_POINTS 3   // VisibilityPointGpu[]: world points for Renderer::visibilityAt (VisibilityPoints.h)
#define PN_SSBO_POINT_VISIBILITY 4  // float[]: V at those points
#define PN_SSBO_SAT 5      // uvec4[]: a summed-area table of depth moments (common/sat.glsl)
#define PN_SSBO_LIGHTS 6   // the lit pass's lights: LightGpu[] (Frame.h), as many as its PN_LIT_LIGHTS
#define PN_SSBO_PAGE_FLAGS 7  // uint[]: per virtual page, set when this frame's pixels need it (passes/virtual_pages.comp.glsl)
#define PN_SSBO_PAGE_LIST 8   // uint count, then the needed pages' indices in the order they were first marked

// Texture units (samplers)
#define PN_TEX_GBUF_POSITION 0  // RGBA32F: world position (m), w = 1 where geometry
#define PN_TEX_GBUF_NORMAL 1    // RGBA16F: shading normal, w = view depth is not stored here
#define PN_TEX_GBUF_GEONORMAL 2 // RGBA16F: geometric normal (for bias and the reference)
#define PN_TEX_GBUF_ALBEDO 3    // RGBA8: base colour
#define PN_TEX_VISIBILITY 4     // R32F: V, 1 = lit
#define PN_TEX_BASECOLOR 5      // a material's base-colour/alpha texture
#define PN_TEX_PAGE_TABLE 6     // R32UI 2D array: a paged projection's page table (0 = not resident, else pool tile + 1)
#define PN_TEX_FILTER0 8        // units 8..15 belong to the active filter
#define PN_TEX_FILTER1 9
#define PN_TEX_FILTER2 10
#define PN_TEX_FILTER3 11
#define PN_TEX_MIN_DEPTH PN_TEX_FILTER2  // a searching filter's min-depth pyramid (shadows/TightSearch.h)
// The core's passes after the filter's (temporal accumulation) reuse the filter's units.
#define PN_TEX_HISTORY PN_TEX_FILTER0           // R32F 2D: the light's V accumulated over earlier frames
#define PN_TEX_PREVIOUS_SURFACE PN_TEX_FILTER1  // RGBA32F: the previous frame's world position per pixel, w = 1 where geometry
#define PN_TEX_PREVIOUS_NORMAL PN_TEX_FILTER2   // RGBA16F: the previous frame's geometric normal per pixel

// Image units
#define PN_IMG_VISIBILITY 0  // r32f output of the visibility pass
#define PN_IMG_OUTPUT 1      // a pass's main output
#define PN_IMG_AUX0 2
#define PN_IMG_AUX1 3

// Explicit uniform locations for per-draw integers (no string look-ups)
#define PN_LOC_OBJECT 0  // int: index into ObjectGpu[]
#define PN_LOC_VIEW 1    // int: shadow view (cascade) being rendered
#define PN_LOC_LEVEL 2   // int: mip level / pass-specific integer
#define PN_LOC_SWITCH 3  // int: a pass-specific switch (0 = off)
#define PN_LOC_FIRST_TRIANGLE 4  // uint: the draw's first triangle in its mesh (gl::drawTriangles' pieces)
#define PN_LOC_PAGE 5    // vec4: a paged shadow pass's page: clip xy scaled by xy, then moved by zw·w

// Limits
#define PN_MAX_SHADOW_VIEWS 48  // views of one light: cascades, cube faces, a clipmap's levels, a paged cube's 6 faces × 8 levels
#define PN_MAX_CASCADES 8       // csm and sdsm allow up to 8 cascades
#define PN_SCREEN_GROUP 8      // workgroup side of full-screen compute passes
