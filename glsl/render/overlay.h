// The overlay's panel (engine/render/overlay_draw.h, glsl/render/overlay.vert and .frag), shared by
// C++ and GLSL: its vertex attributes' locations and its one uniform's.
#ifndef RANRYU_RENDER_OVERLAY_H
#define RANRYU_RENDER_OVERLAY_H

#define RANRYU_ATTR_OVERLAY_POSITION 0   // vec2: display pixels, top-left origin (Dear ImGui's ImDrawVert::pos)
#define RANRYU_ATTR_OVERLAY_UV 1         // vec2: the texture's coordinates
#define RANRYU_ATTR_OVERLAY_COLOR 2      // vec4 from RGBA8, normalised
#define RANRYU_LOC_OVERLAY_DISPLAY 0     // vec4 uniform: xy the display's top-left corner, zw its size (pixels)
#define RANRYU_OVERLAY_TEXTURE_UNIT 0    // the texture a command samples

#endif
