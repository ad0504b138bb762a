#include "gl/gl_objects.h"

namespace tspgl {

void make_vertex_array(const GlApi& gl, GLuint& vao, GLuint& vbo, int components,
                       std::span<const float> data) {
  gl.GenVertexArrays(1, &vao);
  gl.BindVertexArray(vao);
  gl.GenBuffers(1, &vbo);
  gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
  if (!data.empty())
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size_bytes()), data.data(), GL_STATIC_DRAW);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, components, GL_FLOAT, GL_FALSE, GLsizei(components * sizeof(float)),
                         nullptr);
}

void attach_renderbuffer(const GlApi& gl, GLenum attachment, GLuint rb, GLenum format, int width,
                         int height) {
  gl.BindRenderbuffer(GL_RENDERBUFFER, rb);
  gl.RenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, rb);
}

}  // namespace tspgl
