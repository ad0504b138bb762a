#include "jobs/annotate.h"
#include "tsp/report/ticks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace tspgl {
namespace {

// 5 × 7 glyphs, one row per byte (bit 4 = leftmost column).
struct Glyph {
  char c;
  std::array<unsigned char, 7> rows;
};
constexpr int kFieldTitleGap = 12;  // the legend's title sits this far above it, pixels
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}}, {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}}, {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
    {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}}, {'p', {0x00, 0x00, 0x1E, 0x11, 0x1E, 0x10, 0x10}},
    {'x', {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}}, {'y', {0x00, 0x00, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'z', {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
    // For times with units or dates ("2005-08-28 21:00", "0.25 s", "3 hours", "2 days", "5 min").
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'o', {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}}, {'u', {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}},
    {'r', {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}}, {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}},
    {'a', {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}}, {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}}, {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}},
    // The rest of the letters, for field names in the legend ("shock", "QVAPOR", "U_mag").
    {'b', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}}, {'f', {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}},
    {'g', {0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}}, {'j', {0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0C}},
    {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}}, {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'q', {0x00, 0x00, 0x0D, 0x13, 0x0F, 0x01, 0x01}}, {'v', {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'w', {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}}, {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}}, {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
    {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}}, {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
    {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}}, {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
    {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}}, {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}}, {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}}, {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}}, {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}}, {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
    {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}}, {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
    {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}}, {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}}, {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
    {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}}, {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}},
    {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
};
constexpr int kGlyphW = 5, kGlyphH = 7, kAdvance = 6;
constexpr int kLegendWidth = 16, kLegendHeightShare = 2;  // 1/2 of the frame's height, at most
constexpr int kLegendMargin = 10, kTicks = 5;
// Two bars (volume and surface): each this share of the frame's height (percent), this far
// apart (below the title gap), at least this many pixels per tick.
constexpr int kTwoBarsShare = 30, kBarGap = 6, kTickSpacing = 24;
constexpr int kCaptionPad = 4;  // the caption's box reaches this far beyond its text, pixels
constexpr unsigned char kText[3] = {235, 235, 235};
constexpr unsigned char kAxis[3][3] = {{230, 60, 60}, {60, 200, 60}, {80, 120, 255}};

void put(tsp::Image& img, int x, int y, const unsigned char rgb[3]) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  std::uint8_t* p = img.at(x, y);
  p[0] = rgb[0];
  p[1] = rgb[1];
  p[2] = rgb[2];
  p[3] = 255;
}

void line(tsp::Image& img, double x0, double y0, double x1, double y1, const unsigned char rgb[3]) {
  const int n = int(std::ceil(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0)))) + 1;
  if (!(n > 0) || n > 1 << 16) return;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n;
    put(img, int(std::lround(x0 + t * (x1 - x0))), int(std::lround(y0 + t * (y1 - y0))), rgb);
  }
}

// Pixel position of a point in sample coordinates, or false when it lies behind the eye.
bool project(const tsp::Camera& cam, int w, int h, double x, double y, double z, double& px,
             double& py) {
  const glm::dvec4 c = cam.view_projection() * glm::dvec4(x, y, z, 1.0);
  if (!(c.w > 0)) return false;
  px = (c.x / c.w * 0.5 + 0.5) * w;
  py = (1 - (c.y / c.w * 0.5 + 0.5)) * h;  // image rows run downwards
  return std::isfinite(px) && std::isfinite(py);
}

}  // namespace

void draw_text(tsp::Image& img, int x, int y, const std::string& text, const unsigned char rgb[3],
               int scale) {
  for (char ch : text) {
    for (const Glyph& g : kFont) {
      if (g.c != ch) continue;
      for (int r = 0; r < kGlyphH; ++r)
        for (int c = 0; c < kGlyphW; ++c)
          if (g.rows[std::size_t(r)] & (0x10 >> c))
            for (int sy = 0; sy < scale; ++sy)
              for (int sx = 0; sx < scale; ++sx) put(img, x + c * scale + sx, y + r * scale + sy, rgb);
    }
    x += kAdvance * scale;
  }
}

namespace {

// One colour bar at (lx, ly), lh tall: tf's colours (opaque) over its domain, low at the bottom,
// `ticks` round values (0.2 0.4 …, tsp/report/ticks.h) at their places, title above.
void legend_bar(tsp::Image& img, const tsp::TransferFunction& tf, int lx, int ly, int lh,
                const std::string& title, int ticks) {
  const tsp::ValueRange dom = tf.domain();
  for (int r = 0; r < lh; ++r) {
    const double v = dom.hi - (dom.hi - dom.lo) * r / std::max(1, lh - 1);
    const tsp::Rgba c = tf.lookup(v);
    const unsigned char rgb[3] = {
        static_cast<unsigned char>(std::clamp(c.r, 0.f, 1.f) * 255 + 0.5f),
        static_cast<unsigned char>(std::clamp(c.g, 0.f, 1.f) * 255 + 0.5f),
        static_cast<unsigned char>(std::clamp(c.b, 0.f, 1.f) * 255 + 0.5f)};
    for (int x = 0; x < kLegendWidth; ++x) put(img, lx + x, ly + r, rgb);
  }
  // (Moved left as far as a long title, "surface: alpha.water", needs to end inside the frame.)
  if (!title.empty())
    draw_text(img, std::min(lx, img.width - 2 - int(title.size()) * kAdvance), ly - kFieldTitleGap,
              title, kText);
  const std::vector<double> values = tsp::nice_ticks(dom.lo, dom.hi, ticks + 1);
  const double tick_step = values.size() > 1 ? values[1] - values[0] : 1.0;
  for (double v : values) {
    const double u = dom.hi > dom.lo ? (dom.hi - v) / (dom.hi - dom.lo) : 0.0;
    const int y = ly + int(std::lround((lh - 1) * u));
    line(img, lx + kLegendWidth, y, lx + kLegendWidth + 4, y, kText);
    draw_text(img, lx + kLegendWidth + 7, y - 3, tsp::tick_text(v, tick_step), kText);
  }
}

}  // namespace

void annotate_frame(tsp::Image& img, const tsp::Camera& camera, tsp::Dims d,
                    const tsp::TransferFunction& tf, int step, const std::optional<std::string>& time,
                    const std::string& field, const std::string& stretch,
                    const SurfaceLegend& surface) {
  const int w = img.width, h = img.height;
  // Outline: the 12 edges of the volume's box [0, D − 1].
  const double hi[3] = {double(std::max(d.x - 1, 1)), double(std::max(d.y - 1, 1)),
                        double(std::max(d.z - 1, 1))};
  for (int e = 0; e < 12; ++e) {
    const int axis = e / 4, a = (axis + 1) % 3, b = (axis + 2) % 3;
    double p0[3] = {0, 0, 0}, p1[3];
    p0[a] = (e & 1) ? hi[a] : 0;
    p0[b] = (e & 2) ? hi[b] : 0;
    std::copy(p0, p0 + 3, p1);
    p1[axis] = hi[axis];
    double x0, y0, x1, y1;
    if (project(camera, w, h, p0[0], p0[1], p0[2], x0, y0) &&
        project(camera, w, h, p1[0], p1[1], p1[2], x1, y1))
      line(img, x0, y0, x1, y1, kOutlineColour);
  }
  // Axes triad at the origin corner, a quarter of the shortest edge long, labelled.
  const double len = 0.25 * std::min({hi[0], hi[1], hi[2]}) + 1;
  double ox, oy;
  if (project(camera, w, h, 0, 0, 0, ox, oy)) {
    const char* names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      double p[3] = {0, 0, 0}, ex, ey;
      p[a] = len;
      if (!project(camera, w, h, p[0], p[1], p[2], ex, ey)) continue;
      line(img, ox, oy, ex, ey, kAxis[a]);
      draw_text(img, int(ex) + 2, int(ey) - 3, names[a], kAxis[a]);
    }
  }
  // Colour legend on the right: the TF's colours (opaque), low at the bottom, with ticks; with a
  // surface, its map in a second bar below, in the same column.
  const int lx = w - kLegendMargin - kLegendWidth - 48;
  if (!surface.tf) {
    const int lh = std::max(20, h / kLegendHeightShare);
    legend_bar(img, tf, lx, (h - lh) / 2, lh, field, kTicks);
  } else {
    const int lh = std::max(16, h * kTwoBarsShare / 100);
    const int top = std::max(kFieldTitleGap, (h - 2 * lh - kFieldTitleGap - kBarGap) / 2);
    const int ticks = std::clamp(lh / kTickSpacing, 1, kTicks);
    legend_bar(img, tf, lx, top, lh, field, ticks);
    legend_bar(img, *surface.tf, lx, top + lh + kFieldTitleGap + kBarGap, lh,
               "surface: " + surface.field, ticks);
  }
  // Step and time, top left.
  std::string label = "step " + std::to_string(step);
  if (time) label += "  t = " + *time;
  // On an opaque box, so that an outline under it (a stretched axis, a zoom) never crosses it.
  const int text_w = int(std::max(label.size(), stretch.size())) * kAdvance * 2;
  const int box_bottom = (stretch.empty() ? 8 : 26) + kGlyphH * 2 + kCaptionPad;
  for (int y = 8 - kCaptionPad; y < box_bottom; ++y)
    for (int x = 8 - kCaptionPad; x < 8 + text_w + kCaptionPad; ++x) put(img, x, y, kCaptionBox);
  draw_text(img, 8, 8, label, kText, 2);
  if (!stretch.empty()) draw_text(img, 8, 26, stretch, kAxis[2], 2);
}

}  // namespace tspgl
