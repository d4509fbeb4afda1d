#pragma once
// OpenGL 3.3 core declarations without a loader: Mesa's libOpenGL exports every core entry
// point, so prototypes are enough (GL_GLEXT_PROTOTYPES). GLFW must not include GL itself.

#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE
#endif
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
