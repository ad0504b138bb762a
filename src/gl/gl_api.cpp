#include "gl/gl_api.h"

#include <cstdio>

#include "gl/gl_error.h"

namespace tspgl {

namespace {
// glGetError may hold one flag per error kind; more than this many in a row means a lost context.
constexpr int kMaxPendingErrors = 8;
}  // namespace

GlApi load_gl_api(GetProcAddress get_proc) {
  GlApi gl;
  std::string missing;
  // reinterpret_cast between function pointer types is how every GL loader works; the pointer is
  // only called through its true type.
#define TSPGL_LOAD(type, name)                            \
  gl.name = reinterpret_cast<type>(get_proc("gl" #name)); \
  if (!gl.name) missing += (missing.empty() ? "gl" : ", gl") + std::string(#name);
  TSPGL_FUNCTIONS(TSPGL_LOAD)
#undef TSPGL_LOAD
  if (!missing.empty())
    throw tsp::GlError("OpenGL 3.3 core entry points missing from the context: " + missing);
  return gl;
}

std::string gl_error_name(GLenum error) {
  switch (error) {
    case GL_NO_ERROR:
      return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "GL error 0x%04X", unsigned(error));
      return buf;
    }
  }
}

void check_gl(const GlApi& gl, const std::string& what) {
  std::string errors;
  for (int k = 0; k < kMaxPendingErrors; ++k) {
    const GLenum e = gl.GetError();
    if (e == GL_NO_ERROR) break;
    errors += (errors.empty() ? "" : ", ") + gl_error_name(e);
  }
  if (!errors.empty()) throw tsp::GlError("OpenGL error after " + what + ": " + errors);
}

}  // namespace tspgl
