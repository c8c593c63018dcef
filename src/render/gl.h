// OpenGL 3.3 core entry points. libglvnd's libOpenGL exports them directly, so no loader is
// needed; the same calls work under a GLFW window and under an EGL context.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace periflex {

// Compiles and links a program from two files; throws std::runtime_error with the file path and
// the driver's log on failure.
GLuint load_program(const std::string& vertex_path, const std::string& fragment_path);
// The same for one compute shader file (OpenGL 4.3); `compile_hint` is added to the message when
// the shader does not compile (what the caller knows of the likely cause); `defines` (lines of
// #define) are placed after its #version line.
GLuint load_compute_program(const std::string& path, const std::string& compile_hint = "",
                            const std::string& defines = "");

// Throws std::runtime_error naming `where` when glGetError reports an error.
void check_gl(const char* where);

}  // namespace periflex
