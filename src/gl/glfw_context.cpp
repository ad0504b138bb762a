// The window back end: GLFW (X11 or Wayland) with an OpenGL 3.3 core context, for the player.
// GL functions come from glfwGetProcAddress (docs/rendering.md).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>

#include "gl/context.h"
#include "gl/gl_error.h"

namespace tspgl {

namespace {

constexpr int kMajor = 3, kMinor = 3;

// GLFW reports failures through a callback; the last message goes into our exceptions.
std::string& last_glfw_error() {
  static std::string message;
  return message;
}

void on_glfw_error(int code, const char* description) {
  last_glfw_error() = std::string(description ? description : "unknown") + " (GLFW error " +
                      std::to_string(code) + ")";
}

// GLFW is initialised while at least one window exists and terminated with the last one.
int& live_windows() {
  static int count = 0;
  return count;
}

void acquire_glfw() {
  if (live_windows() == 0) {
    glfwSetErrorCallback(on_glfw_error);
    last_glfw_error().clear();
    if (!glfwInit())
      throw tsp::GlError("cannot open a window: GLFW could not initialise (" + last_glfw_error() +
                         ")");
  }
  ++live_windows();
}

void release_glfw() {
  if (--live_windows() == 0) glfwTerminate();
}

class GlfwContext final : public GlContext {
 public:
  GlfwContext(int w, int h, const std::string& title, bool visible) {
    acquire_glfw();
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, kMajor);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, kMinor);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    last_glfw_error().clear();
    window_ = glfwCreateWindow(w, h, title.c_str(), nullptr, nullptr);
    if (!window_) {
      release_glfw();
      throw tsp::GlError("cannot open a " + std::to_string(w) + "x" + std::to_string(h) +
                         " window with an OpenGL 3.3 core context (" + last_glfw_error() + ")");
    }
    try {
      make_current();
      load(&glfwGetProcAddress, "GLFW");
    } catch (...) {
      destroy();
      throw;
    }
  }
  ~GlfwContext() override { destroy(); }

  void make_current() override { glfwMakeContextCurrent(window_); }
  // The framebuffer size, which differs from the window size on high-DPI screens.
  int width() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
  }
  int height() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
  }
  GetProcAddress proc_address_function() const override { return &glfwGetProcAddress; }
  std::string kind() const override { return "GLFW"; }
  void swap_buffers() override { glfwSwapBuffers(window_); }
  void poll_events() override { glfwPollEvents(); }
  void wait_events(double timeout_s) override { glfwWaitEventsTimeout(timeout_s); }
  bool should_close() const override { return glfwWindowShouldClose(window_); }
  void* native_window() const override { return window_; }

 private:
  void destroy() {
    if (!window_) return;
    if (glfwGetCurrentContext() == window_) glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(window_);
    window_ = nullptr;
    release_glfw();
  }

  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> create_window_context(int width, int height, const std::string& title,
                                                 bool visible) {
  if (width < 1 || height < 1)
    throw tsp::UsageError("window size " + std::to_string(width) + "x" + std::to_string(height) +
                          " is invalid, expected at least 1x1");
  return std::make_unique<GlfwContext>(width, height, title, visible);
}

}  // namespace tspgl
