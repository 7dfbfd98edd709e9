#version 430
// The overlay's panel: the vertex colour times the command's texture (the font atlas, whose white
// texel serves the untextured shapes). Blended over the picture by the draw's state (overlay_draw.h).
#include "overlay.h"

in vec2 v_uv;
in vec4 v_color;
layout(binding = RANRYU_OVERLAY_TEXTURE_UNIT) uniform sampler2D tex;
layout(location = 0) out vec4 out_color;

void main() { out_color = v_color * texture(tex, v_uv); }
