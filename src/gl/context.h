// src/gl: OpenGL contexts, our loader and shaders; may include tsp/.
// An OpenGL 3.3 core context with its default framebuffer: offscreen (OSMesa or EGL, headless;
// used by `tspplay render` and the tests: gl/headless.h) or a window (GLFW; used by the player).
#pragma once
#include <memory>
#include <string>

#include "gl/gl_api.h"
#include "tsp/report/image.h"

namespace tspgl {

/// A GL context and the GL functions loaded for it. Owns the context; not copyable; use it from
/// the thread that made it current.
class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// Makes this context current on the calling thread. Throws tsp::GlError.
  virtual void make_current() = 0;
  /// Width of the default framebuffer in pixels.
  virtual int width() const = 0;
  /// Height of the default framebuffer in pixels.
  virtual int height() const = 0;
  /// The back end's get-proc-address (OSMesaGetProcAddress or glfwGetProcAddress), for other
  /// loaders such as Dear ImGui's.
  virtual GetProcAddress proc_address_function() const = 0;
  /// What kind of context this is, for reports: "OSMesa", "EGL device 0 (software)", "GLFW".
  virtual std::string kind() const = 0;
  /// Shows the back buffer (windows); nothing offscreen.
  virtual void swap_buffers() {}
  /// Processes pending window events (windows); nothing offscreen.
  virtual void poll_events() {}
  /// Sleeps until a window event arrives or timeout_s passes, then processes the events
  /// (windows); returns at once offscreen.
  virtual void wait_events(double timeout_s) { (void)timeout_s; }
  /// Whether the user asked to close the window; always false offscreen.
  virtual bool should_close() const { return false; }
  /// The GLFWwindow* of a window context (for Dear ImGui's GLFW back end); null offscreen.
  virtual void* native_window() const { return nullptr; }

  /// The GL functions of this context (valid while it is current).
  const GlApi& gl() const { return gl_; }
  /// Waits until GL has finished all commands. Throws tsp::GlError on a pending GL error.
  void finish();
  /// Reads the canvas's colour buffer as RGBA8, top row first. Throws tsp::GlError.
  tsp::Image read_pixels();
  /// Reads the w × h rectangle whose lower-left corner is (x, y) (GL window coordinates) of the
  /// canvas as RGBA8, top row first; asserts it lies inside. Throws tsp::GlError.
  tsp::Image read_pixels(int x, int y, int w, int h);
  /// The framebuffer frames are resolved into and read_pixels reads — the canvas: the default
  /// framebuffer (0), or the OffscreenCanvas in use (gl/offscreen_canvas.h).
  GLuint canvas_framebuffer() const { return canvas_.fbo; }
  /// The canvas's width in pixels (the default framebuffer's without an offscreen canvas).
  int canvas_width() const { return canvas_.fbo ? canvas_.width : width(); }
  /// The canvas's height in pixels (the default framebuffer's without an offscreen canvas).
  int canvas_height() const { return canvas_.fbo ? canvas_.height : height(); }
  /// "RENDERER, GL VERSION" of the context, for reports.
  std::string describe() const;
  /// GL_VENDOR of the context, for reports.
  std::string vendor() const;

 protected:
  GlContext() = default;
  /// Loads the GL table through get_proc and checks for a 3.3 core context; call once the
  /// context is current. Throws tsp::GlError.
  void load(GetProcAddress get_proc, const std::string& backend);

 private:
  friend class CanvasScope;
  /// The canvas: a framebuffer object and its size, or fbo 0 for the default framebuffer.
  struct Canvas {
    GLuint fbo = 0;
    int width = 0, height = 0;
  };
  GlApi gl_;
  Canvas canvas_;
};

/// A headless OSMesa context, OpenGL 3.3 core profile, w × h RGBA8 framebuffer; made current.
/// Throws tsp::UsageError for a size outside [1, OSMesa's maximum], tsp::GlError when OSMesa
/// cannot create a 3.3 core context.
std::unique_ptr<GlContext> create_offscreen_context(int width, int height);

/// A GLFW window with an OpenGL 3.3 core context (hidden unless visible), made current. Throws
/// tsp::UsageError for a non-positive size, tsp::GlError when there is no display or no such
/// context. Call from the main thread.
std::unique_ptr<GlContext> create_window_context(int width, int height, const std::string& title,
                                                 bool visible);

}  // namespace tspgl
