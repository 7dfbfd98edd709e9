// Spray and foam (glsl/render/spray.vert, spray.frag; render::Renderer::draw_spray): the constants
// C++ and GLSL share.
#ifndef RANRYU_RENDER_SPRAY_H
#define RANRYU_RENDER_SPRAY_H
#define RANRYU_LOC_SPRAY 10      // vec4 uniform: x e_min (m²/s²), the energy at which a sprite starts to show
#define RANRYU_SPRAY_ALPHA 0.8   // the most opaque a sprite gets (full at e >= 2 e_min)
#endif
