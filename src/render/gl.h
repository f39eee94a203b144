// OpenGL 3.3 core through the GL vendor-neutral dispatch library (libOpenGL), which serves
// EGL contexts (offscreen) and GLX contexts (GLFW windows) alike, so no loader is needed.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
