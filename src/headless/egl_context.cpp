#include "headless/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "render/gl.h"

namespace periflex {

namespace {

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%04x", e);
      return buf;
    }
  }
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// eglTerminate would destroy every context of a display, so displays are initialised once per
// process and counted; the last user terminates. Never destroyed: a context held by a static
// object (a shared compute context) may close its display after the other statics are gone.
std::mutex& display_mutex() {
  static auto* m = new std::mutex;
  return *m;
}
std::map<EGLDisplay, int>& display_users() {
  static auto* users = new std::map<EGLDisplay, int>;
  return *users;
}

// Opens and initialises a display, trying the platforms in order of preference.
EGLDisplay open_display(std::string& platform, std::string& tried) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto try_init = [&](EGLDisplay d, const char* name) -> EGLDisplay {
    tried += std::string(tried.empty() ? "" : ", ") + name;
    if (d == EGL_NO_DISPLAY) return EGL_NO_DISPLAY;
    std::lock_guard<std::mutex> lock(display_mutex());
    auto& users = display_users();
    if (users[d] == 0) {
      EGLint major = 0, minor = 0;
      if (!eglInitialize(d, &major, &minor)) {
        users.erase(d);
        tried += std::string(" (") + egl_error_name(eglGetError()) + ")";
        return EGL_NO_DISPLAY;
      }
    }
    ++users[d];
    platform = name;
    return d;
  };

  // 1. Mesa's surfaceless platform: no X, no Wayland, no device node needed
  if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = try_init(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                            "surfaceless");
    if (d != EGL_NO_DISPLAY) return d;
  }
  // 2. an EGL device (a GPU, or the software device)
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (get_platform_display && query_devices && has_extension(client, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (query_devices(8, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = try_init(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device");
        if (d != EGL_NO_DISPLAY) return d;
      }
    }
  }
  // 3. whatever the default display is
  return try_init(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default display");
}

void close_display(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(display_mutex());
  auto& users = display_users();
  if (--users[d] <= 0) {
    users.erase(d);
    eglTerminate(d);
  }
}

}  // namespace

EglContext::EglContext(int major, int minor) {
  std::string platform, tried;
  EGLDisplay display = open_display(platform, tried);
  if (display == EGL_NO_DISPLAY)
    throw std::runtime_error("EGL: no usable display (tried " + tried + "); off-screen rendering needs Mesa's EGL "
                             "(libegl-mesa0) or a GPU driver with EGL");
  display_ = display;

  auto fail = [&](const std::string& step) {
    const std::string error = egl_error_name(eglGetError());
    close_display(display);
    display_ = nullptr;
    throw std::runtime_error("EGL (" + platform + "): " + step + " failed: " + error);
  };

  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");

  // any config that renders desktop OpenGL; the surface type does not matter without a surface
  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                                   EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_SURFACE_TYPE, EGL_DONT_CARE,
                                   EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attribs, &config, 1, &configs) || configs < 1)
    fail("eglChooseConfig (no OpenGL config)");

  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
  if (context == EGL_NO_CONTEXT)
    fail("eglCreateContext (OpenGL " + std::to_string(major) + "." + std::to_string(minor) + " core)");
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    context_ = nullptr;
    fail("eglMakeCurrent without a surface");
  }

  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  description_ = "platform: " + platform + "; GL: " + (version ? version : "?") +
                 "; renderer: " + (renderer ? renderer : "?");
}

EglContext::~EglContext() {
  if (!display_) return;
  EGLDisplay display = static_cast<EGLDisplay>(display_);
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_) eglDestroyContext(display, static_cast<EGLContext>(context_));
  close_display(display);
}

void EglContext::make_current() {
  if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(context_)))
    throw std::runtime_error("EGL: eglMakeCurrent failed: " + egl_error_name(eglGetError()));
}

EglContext::Scope::Scope(EglContext& context) : Scope(context, std::nothrow) {
  if (!current_) throw std::runtime_error("EGL: eglMakeCurrent failed: " + egl_error_name(error_));
}

EglContext::Scope::Scope(EglContext& context, std::nothrow_t) {
  const EGLContext mine = static_cast<EGLContext>(context.context_);
  context_ = eglGetCurrentContext();
  if (context_ == mine) return;
  display_ = eglGetCurrentDisplay();
  draw_ = eglGetCurrentSurface(EGL_DRAW);
  read_ = eglGetCurrentSurface(EGL_READ);
  switched_ = eglMakeCurrent(static_cast<EGLDisplay>(context.display_), EGL_NO_SURFACE, EGL_NO_SURFACE, mine);
  current_ = switched_;
  if (!switched_) error_ = eglGetError();
}

EglContext::Scope::~Scope() {
  if (!switched_) return;
  // the thread's own context back, or none (so that another thread may take this one next)
  if (context_ != EGL_NO_CONTEXT)
    eglMakeCurrent(static_cast<EGLDisplay>(display_), static_cast<EGLSurface>(draw_), static_cast<EGLSurface>(read_),
                   static_cast<EGLContext>(context_));
  else
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

void EglContext::release() {
  eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace periflex
