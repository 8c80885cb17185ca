#pragma once
// The G-buffer's attachments (Renderer.cpp's kScreenTextures, GBufferData), written by the
// surfaces (passes/gbuffer.frag.glsl) and by the background (passes/gbuffer_background.frag.glsl).
// PN_GBUFFER_TRIANGLES (0/1, a define): whether the frame records triangle ids
// (RenderOptions::triangleIds); without them attachment 4 is not a draw buffer.
layout(location = 0) out vec4 o_position;   // xyz world (m); w = 1 on a surface, 0 on background
layout(location = 1) out vec4 o_normal;     // xyz shading normal
layout(location = 2) out vec4 o_geoNormal;  // xyz geometric normal
layout(location = 3) out vec4 o_albedo;     // rgb linear base colour
#if PN_GBUFFER_TRIANGLES
// (object index + 1, triangle index in the object's mesh); 0 = none (background).
layout(location = 4) out uvec2 o_triangle;
#endif
