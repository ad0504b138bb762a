// The headless GPU back end: EGL on a device (EGL_EXT_device_enumeration, EGL_EXT_platform_device)
// with a pbuffer the size of the image, so a GPU node renders without a display; Mesa's software
// device (llvmpipe) serves it where there is no GPU, so the suite runs it. GL functions come from
// eglGetProcAddress (EGL_KHR_client_get_all_proc_addresses), never from libGL. Built only where
// EGL's headers are (TSPPLAY_HAS_EGL); elsewhere a request for EGL falls back to OSMesa.
#include "gl/headless.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gl/gl_error.h"
#include "tsp/core/error.h"

#if TSPPLAY_HAS_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

namespace tspgl {

namespace {

constexpr int kMaxDevices = 16;
constexpr int kDepthBits = 24;
constexpr int kMajor = 3, kMinor = 3;

#if TSPPLAY_HAS_EGL

// The device entry points (extensions: looked up at run time).
struct DeviceApi {
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display = nullptr;
  bool ok() const { return query_devices && query_device_string && platform_display; }
};

DeviceApi device_api() {
  DeviceApi api;
  api.query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  api.query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  api.platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  return api;
}

std::vector<EGLDeviceEXT> device_handles(const DeviceApi& api) {
  if (!api.ok()) return {};
  EGLDeviceEXT devices[kMaxDevices];
  EGLint n = 0;
  if (!api.query_devices(kMaxDevices, devices, &n) || n < 0) return {};
  return std::vector<EGLDeviceEXT>(devices, devices + n);  // (braces would make a 2-element list)
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t len = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += len)
    if ((p == list || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0')) return true;
  return false;
}

EglDevice describe_device(const DeviceApi& api, EGLDeviceEXT d, int index) {
  EglDevice e;
  e.index = index;
  const char* ext = api.query_device_string(d, EGL_EXTENSIONS);
  e.software = has_extension(ext, "EGL_MESA_device_software");
  const char* node = has_extension(ext, "EGL_EXT_device_drm_render_node")
                         ? api.query_device_string(d, EGL_DRM_RENDER_NODE_FILE_EXT)
                         : nullptr;
  e.name = e.software ? "software" : node ? node : "device";
  return e;
}

std::vector<EglDevice> describe_devices(const DeviceApi& api,
                                        const std::vector<EGLDeviceEXT>& handles) {
  std::vector<EglDevice> out;
  for (std::size_t i = 0; i < handles.size(); ++i)
    out.push_back(describe_device(api, handles[i], int(i)));
  return out;
}

std::string hex(EGLint code) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", unsigned(code));
  return buf;
}

ProcAddress egl_proc(const char* name) { return eglGetProcAddress(name); }

class EglContext final : public GlContext {
 public:
  // Throws tsp::GlError naming the step that failed.
  EglContext(const DeviceApi& api, EGLDeviceEXT device, const EglDevice& info, int w, int h)
      : width_(w), height_(h) {
    kind_ = "EGL device " + std::to_string(info.index) + " (" + info.name + ")";
    display_ = api.platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor))
      throw tsp::GlError(kind_ + ": eglInitialize failed (" + hex(eglGetError()) + ")");
    // clang-format off
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                     EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, kDepthBits,
                                     EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, kMajor,
                                      EGL_CONTEXT_MINOR_VERSION, kMinor,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    const EGLint surface_attribs[] = {EGL_WIDTH, w, EGL_HEIGHT, h, EGL_NONE};
    // clang-format on
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &configs) || configs < 1)
      throw tsp::GlError(kind_ + ": no RGBA8 + depth pbuffer configuration for desktop OpenGL");
    if (!eglBindAPI(EGL_OPENGL_API))
      throw tsp::GlError(kind_ + ": desktop OpenGL is not available (" + hex(eglGetError()) + ")");
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
    if (context_ == EGL_NO_CONTEXT)
      throw tsp::GlError(kind_ + ": no OpenGL 3.3 core profile context (" + hex(eglGetError()) +
                         ")");
    surface_ = eglCreatePbufferSurface(display_, config, surface_attribs);
    if (surface_ == EGL_NO_SURFACE)
      throw tsp::GlError(kind_ + ": no " + std::to_string(w) + "x" + std::to_string(h) +
                         " pbuffer (" + hex(eglGetError()) + ")");
    make_current();
    load(&egl_proc, kind_);
  }

  // The display is left initialised: EGL hands every context on a device the same display, and
  // eglTerminate would end the others'.
  ~EglContext() override {
    if (eglGetCurrentContext() == context_)
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
  }

  void make_current() override {
    if (!eglMakeCurrent(display_, surface_, surface_, context_))
      throw tsp::GlError(kind_ + ": eglMakeCurrent failed (" + hex(eglGetError()) + ")");
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  GetProcAddress proc_address_function() const override { return &egl_proc; }
  std::string kind() const override { return kind_; }

 private:
  int width_, height_;
  std::string kind_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
};

#endif  // TSPPLAY_HAS_EGL

// The device index asked for: device, else TSPPLAY_EGL_DEVICE, else −1. Throws UsageError.
int asked_device(int device) {
  if (device < -1) throw tsp::UsageError("--gpu " + std::to_string(device) + ": expected 0 or more");
  if (device >= 0) return device;
  const char* env = std::getenv("TSPPLAY_EGL_DEVICE");
  if (!env || !*env) return -1;
  char* end = nullptr;
  const long v = std::strtol(env, &end, 10);
  if (*end != '\0' || v < 0 || v >= kMaxDevices)
    throw tsp::UsageError("TSPPLAY_EGL_DEVICE=" + std::string(env) + ": expected a device index 0.." +
                          std::to_string(kMaxDevices - 1));
  return int(v);
}

// TSPPLAY_EGL_DEVICE_SLOT (set by tspplay-mpi render: the rank's index on its node), else 0; a
// value that is not a small non-negative integer counts as 0. Never throws.
int device_slot() {
  const char* env = std::getenv("TSPPLAY_EGL_DEVICE_SLOT");
  if (!env || !*env) return 0;
  char* end = nullptr;
  const long v = std::strtol(env, &end, 10);
  return *end == '\0' && v >= 0 && v < (1 << 20) ? int(v) : 0;
}

std::string device_list(const std::vector<EglDevice>& devices) {
  std::string s;
  for (const EglDevice& d : devices)
    s += (s.empty() ? "" : ", ") + std::to_string(d.index) + " " + d.name;
  return devices.empty() ? "none" : s;
}

}  // namespace

std::string to_string(HeadlessGl gl) {
  return gl == HeadlessGl::egl ? "egl" : gl == HeadlessGl::osmesa ? "osmesa" : "auto";
}

HeadlessGl parse_headless_gl(const std::string& text, const std::string& option) {
  if (text == "auto") return HeadlessGl::automatic;
  if (text == "egl") return HeadlessGl::egl;
  if (text == "osmesa") return HeadlessGl::osmesa;
  throw tsp::UsageError(option + " " + text + ": expected auto, egl or osmesa");
}

std::vector<EglDevice> egl_devices() {
#if TSPPLAY_HAS_EGL
  const DeviceApi api = device_api();
  return describe_devices(api, device_handles(api));
#else
  return {};
#endif
}

std::unique_ptr<GlContext> create_headless_context(int width, int height, HeadlessGl gl,
                                                   int device, std::string* note) {
  if (note) note->clear();
  if (width < 1 || height < 1) return create_offscreen_context(width, height);  // (its message)
  const int asked = gl == HeadlessGl::osmesa ? -1 : asked_device(device);
  if (gl == HeadlessGl::osmesa) return create_offscreen_context(width, height);
  const bool insist = gl == HeadlessGl::egl || asked >= 0;  // else: quietly OSMesa
  std::string why;
#if TSPPLAY_HAS_EGL
  const DeviceApi api = device_api();
  const std::vector<EGLDeviceEXT> handles = device_handles(api);
  const std::vector<EglDevice> devices = describe_devices(api, handles);
  int pick = asked;
  if (pick < 0) {  // the first GPU, or with a slot (one per MPI rank on a node) GPU slot mod GPUs
    std::vector<int> gpus;
    for (const EglDevice& d : devices)
      if (!d.software) gpus.push_back(d.index);
    if (!gpus.empty()) pick = gpus[std::size_t(device_slot()) % gpus.size()];
  }
  if (pick < 0 && gl == HeadlessGl::egl && !devices.empty()) pick = 0;
  if (!api.ok()) {
    why = "EGL has no device enumeration (EGL_EXT_device_enumeration, EGL_EXT_platform_device)";
  } else if (pick >= int(devices.size())) {
    why = "EGL device " + std::to_string(pick) + " does not exist (devices: " +
          device_list(devices) + ")";
  } else if (pick >= 0) {
    try {
      return std::make_unique<EglContext>(api, handles[std::size_t(pick)],
                                          devices[std::size_t(pick)], width, height);
    } catch (const tsp::GlError& e) {
      why = e.what();
    }
  } else if (insist) {
    why = "EGL enumerates no device";
  }
#else
  why = "this tspplay was built without EGL (install libegl-dev and rebuild)";
#endif
  if (insist && note) *note = why + "; drawing with OSMesa instead";
  return create_offscreen_context(width, height);
}

}  // namespace tspgl
