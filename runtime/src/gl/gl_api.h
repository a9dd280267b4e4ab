#pragma once
// The OpenGL 4.5 core API. libglvnd's libOpenGL exports every core entry point and dispatches to
// the vendor library (Mesa or NVIDIA) of the current EGL context, so no loader is needed.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
