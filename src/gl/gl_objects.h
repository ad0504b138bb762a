// Set-ups of GL objects the renderers and tests share: a vertex array over one float buffer and a
// renderbuffer attached to the bound framebuffer.
#pragma once
#include <span>

#include "gl/gl_api.h"

namespace tspgl {

/// Creates vertex array vao and buffer vbo, leaves both bound, and reads attribute 0 as
/// `components` tightly packed floats per vertex from vbo; fills vbo with `data` (GL_STATIC_DRAW)
/// when data is not empty.
void make_vertex_array(const GlApi& gl, GLuint& vao, GLuint& vbo, int components,
                       std::span<const float> data = {});

/// Gives renderbuffer rb storage of `format` at width × height and attaches it to the bound
/// framebuffer at `attachment` (e.g. GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT).
void attach_renderbuffer(const GlApi& gl, GLenum attachment, GLuint rb, GLenum format, int width,
                         int height);

}  // namespace tspgl
