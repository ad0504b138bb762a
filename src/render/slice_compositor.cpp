#include "render/slice_compositor.h"

#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_error.h"

namespace tspgl {

namespace {
constexpr int kVolumeUnit = 0;  // texture unit of the brick (or whole-volume) texture
constexpr int kTfUnit = 1;      // texture unit of the transfer-function lookup
}  // namespace

std::array<float, 4> flat_colour(const tsp::Rgba& c, double spacing) {
  const float a = corrected_alpha(c.a, spacing);
  return {c.r * a, c.g * a, c.b * a, a};
}

SliceCompositor::SliceCompositor(GlContext& ctx)
    : ctx_(ctx),
      gl_(ctx.gl()),
      textured_(load_program(ctx.gl(), "slice.vert", "slice_textured.frag")),
      flat_(load_program(ctx.gl(), "slice.vert", "slice_flat.frag")),
      tf_(ctx.gl()),
      target_(ctx) {
  gl_.GenVertexArrays(1, &vao_);
  gl_.BindVertexArray(vao_);
  gl_.GenBuffers(1, &vbo_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  textured_.use();
  gl_.Uniform1i(textured_.uniform("volume"), kVolumeUnit);
  gl_.Uniform1i(textured_.uniform("transfer_function"), kTfUnit);
  check_gl(gl_, "setting up the slice compositor");
}

SliceCompositor::~SliceCompositor() {
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteVertexArrays(1, &vao_);
}

void SliceCompositor::set_transfer_function(const tsp::TransferFunction& tf,
                                            tsp::ValueRange quantized) {
  tf_.set(tf, quantized);
}

void SliceCompositor::begin_frame(const tsp::Camera& camera, const RenderSettings& settings) {
  ctx_.make_current();
  target_.bind();
  gl_.ClearColor(settings.background[0], settings.background[1], settings.background[2], 1.f);
  gl_.Clear(GL_COLOR_BUFFER_BIT);
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.Enable(GL_BLEND);
  // Premultiplied colours composited back to front with "over"; alpha stays 1 (opaque image).
  gl_.BlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl_.BindVertexArray(vao_);
  const glm::mat4 vp(camera.view_projection());
  for (const Program* p : {&textured_, &flat_}) {
    p->use();
    gl_.UniformMatrix4fv(p->uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  }
  textured_.use();
  gl_.Uniform2f(textured_.uniform("tf_map"), tf_.scale(), tf_.offset());
  tf_.bind(kTfUnit, settings.spacing);
  gl_.ActiveTexture(GL_TEXTURE0 + kVolumeUnit);
}

void SliceCompositor::upload(const tsp::PolygonSoup& soup) {
  vertices_.assign(soup.xyz.begin(), soup.xyz.end());
  firsts_.resize(soup.size());
  counts_.resize(soup.size());
  GLint next = 0;
  for (std::size_t i = 0; i < soup.size(); ++i) {
    firsts_[i] = next;
    counts_[i] = GLsizei(soup.counts[i]);
    next += counts_[i];
  }
  gl_.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices_.size() * sizeof(float)), vertices_.data(),
                 GL_STREAM_DRAW);
}

void SliceCompositor::draw(const std::vector<DrawItem>& items) {
  const Program* current = nullptr;
  for (const DrawItem& it : items) {
    if (it.polygon_count == 0) continue;
    const Program* want = it.texture ? &textured_ : &flat_;
    if (want != current) {
      want->use();
      current = want;
    }
    if (it.texture) {
      const tsp::Box& s = it.samples;
      gl_.BindTexture(GL_TEXTURE_3D, it.texture);
      gl_.Uniform3f(textured_.uniform("tex_origin"), float(s.lo[0]) - 0.5f,
                    float(s.lo[1]) - 0.5f, float(s.lo[2]) - 0.5f);
      gl_.Uniform3f(textured_.uniform("tex_scale"), 1.f / float(s.size(0)),
                    1.f / float(s.size(1)), 1.f / float(s.size(2)));
    } else {
      gl_.Uniform4fv(flat_.uniform("flat_colour"), 1, it.colour.data());
    }
    gl_.MultiDrawArrays(GL_TRIANGLE_FAN, firsts_.data() + it.first_polygon,
                        counts_.data() + it.first_polygon, it.polygon_count);
  }
}

void SliceCompositor::end_frame() {
  target_.resolve();
  ctx_.finish();
}

}  // namespace tspgl
