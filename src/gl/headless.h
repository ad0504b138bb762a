// src/gl: OpenGL contexts, our loader and shaders; may include tsp/.
// Which GL draws headless frames (`render`, `bench`, `--gl auto|egl|osmesa`): EGL on a device (a
// GPU node without a display, as ParaView and VTK render there; Mesa's software device where
// there is no GPU) or OSMesa. A request EGL cannot serve falls back to OSMesa with a note.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "gl/context.h"

namespace tspgl {

/// `--gl`: which GL draws headless frames.
enum class HeadlessGl {
  automatic,  ///< EGL on a hardware device when one is found, else OSMesa
  egl,        ///< EGL (on a hardware device when one is found, else Mesa's software device)
  osmesa,     ///< OSMesa, always on the CPU
};

/// The option text of gl: auto, egl or osmesa. Never throws.
std::string to_string(HeadlessGl gl);
/// Parses auto|egl|osmesa. Throws tsp::UsageError naming option.
HeadlessGl parse_headless_gl(const std::string& text, const std::string& option);

/// One device EGL enumerates.
struct EglDevice {
  int index = 0;          ///< its place in the enumeration (`--gpu N`)
  bool software = false;  ///< Mesa's software device (llvmpipe: EGL_MESA_device_software)
  std::string name;       ///< its DRM render node, or "software"
};

/// The devices EGL enumerates here; empty without EGL, without device enumeration
/// (EGL_EXT_device_enumeration, EGL_EXT_platform_device) or in a build without EGL. Never throws;
/// thread-safe.
std::vector<EglDevice> egl_devices();

/// A headless w × h context, made current: EGL on device `device` (an index of egl_devices(); −1:
/// the TSPPLAY_EGL_DEVICE environment variable when set, else the first hardware device, else for
/// `egl` the first device) or OSMesa, by gl's rule. When EGL was asked for (egl, or a device
/// index given) but cannot serve — no EGL, no such device, no 3.3 core context — it falls back to
/// OSMesa and *note says why in one line; "" otherwise. kind() names what was made. Throws what
/// create_offscreen_context throws, tsp::UsageError for a negative device other than −1 or a bad
/// TSPPLAY_EGL_DEVICE.
std::unique_ptr<GlContext> create_headless_context(int width, int height, HeadlessGl gl,
                                                   int device, std::string* note);

}  // namespace tspgl
