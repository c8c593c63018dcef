#include "render/gl.h"

#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>

namespace periflex {

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read shader " + path + " (is PERIFLEX_ROOT right?)");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `hint` follows the driver's log when the shader does not compile; `defines` (lines of #define)
// go after the source's first line, its #version.
GLuint compile(GLenum type, const std::string& path, const std::string& hint = "", const std::string& defines = "") {
  std::string source = read_text(path);
  if (!defines.empty()) {
    const size_t line_end = source.find('\n');
    source.insert(line_end == std::string::npos ? source.size() : line_end + 1, defines);
  }
  const char* text = source.c_str();
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error("shader " + path + " does not compile:\n" + log + hint);
  }
  return shader;
}

// Links the compiled shaders (deleting them) into a program; `what` names them in the error.
GLuint link(std::initializer_list<GLuint> shaders, const std::string& what) {
  GLuint program = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : shaders) glDeleteShader(shader);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw std::runtime_error(what + " do not link:\n" + log);
  }
  return program;
}

}  // namespace

GLuint load_program(const std::string& vertex_path, const std::string& fragment_path) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_path);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_path);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  return link({vs, fs}, "shaders " + vertex_path + " + " + fragment_path);
}

GLuint load_compute_program(const std::string& path, const std::string& compile_hint, const std::string& defines) {
  return link({compile(GL_COMPUTE_SHADER, path, compile_hint, defines)}, "compute shader " + path);
}

void check_gl(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", e);
    throw std::runtime_error(std::string("OpenGL error ") + code + " in " + where);
  }
}

}  // namespace periflex
