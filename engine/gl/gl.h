#pragma once
// The GL 4.3 core API. Entry points come straight from GLVND's libOpenGL, which dispatches to the
// current context's vendor (NVIDIA through EGL, Mesa through EGL or GLX): no loader is needed.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
