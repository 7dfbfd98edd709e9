#version 430
// The overlay's panel (engine/render/overlay_draw.h): a vertex in display pixels with a top-left
// origin, as Dear ImGui lays the panel out, to clip space over the display rectangle (x0, y0, w, h):
//     ndc = (2 (x − x0)/w − 1, 1 − 2 (y − y0)/h).
#include "overlay.h"

layout(location = RANRYU_ATTR_OVERLAY_POSITION) in vec2 in_position;
layout(location = RANRYU_ATTR_OVERLAY_UV) in vec2 in_uv;
layout(location = RANRYU_ATTR_OVERLAY_COLOR) in vec4 in_color;
layout(location = RANRYU_LOC_OVERLAY_DISPLAY) uniform vec4 display;

out vec2 v_uv;
out vec4 v_color;

void main() {
    vec2 t = (in_position - display.xy) / display.zw;
    gl_Position = vec4(2.0 * t.x - 1.0, 1.0 - 2.0 * t.y, 0.0, 1.0);
    v_uv = in_uv;
    v_color = in_color;
}
