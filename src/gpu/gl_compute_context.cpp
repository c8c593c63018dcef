#include "gpu/gl_compute_context.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "render/gl.h"

namespace periflex {

namespace {

// An EGL context of OpenGL 4.3, the first version with compute shaders; the error says so
EglContext make_compute_context() {
  try {
    return EglContext(4, 3);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("no OpenGL 4.3 context for compute shaders: ") + e.what());
  }
}

}  // namespace

unsigned load_compute_program(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read shader " + path + " (is PERIFLEX_ROOT right?)");
  std::stringstream text;
  text << in.rdbuf();
  const std::string source = text.str();
  const char* chars = source.c_str();
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderSource(shader, 1, &chars, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error("compute shader " + path + " does not compile (does the driver have fp64?):\n" + log);
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw std::runtime_error("compute shader " + path + " does not link:\n" + log);
  }
  return program;
}

GlComputeContext::GlComputeContext(const std::string& resource_root) : egl_(make_compute_context()) {
  EglContext::Scope current(egl_);
  const auto path = std::filesystem::path(resource_root) / "shaders" / "pd_bond_forces.comp";
  bond_force_program_ = load_compute_program(path.string());
  description_ = "OpenGL compute fp64; " + egl_.description();
  // current on no thread between passes: each pass takes it on the thread it runs on
  egl_.release();
}

GlComputeContext::~GlComputeContext() {
  EglContext::Scope current(egl_);
  glDeleteProgram(bond_force_program_);
}

}  // namespace periflex
