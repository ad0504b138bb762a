#include "tsp/report/svg_plot.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <fstream>
#include <limits>

#include "tsp/core/error.h"
#include "tsp/core/number_text.h"
#include "tsp/core/temp_output.h"

namespace tsp {

namespace {

constexpr double kMarginLeft = 70, kMarginRight = 190, kMarginTop = 40, kMarginBottom = 55;
// Legend layout: the gap, swatch and padding before a label, and a label character's width.
constexpr double kLegendSwatch = 12 + 26 + 12, kCharWidth = 7.2;
constexpr double kMinPlotWidth = 360;
constexpr int kTargetTicks = 6;
constexpr double kMarkerRadius = 3.5;
// Distinguishable colours (Okabe–Ito), cycled.
constexpr const char* kColours[] = {"#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442",
                                    "#0072B2", "#D55E00", "#CC79A7", "#999999"};

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string num(double v) {
  return number_text(v, "%.2f");
}

std::string tick_label(double v) {
  return number_text(std::abs(v) < 1e-12 ? 0.0 : v);
}

// A "nice" tick step (1, 2 or 5 × 10^k) giving about kTargetTicks ticks over span.
double nice_step(double span) {
  const double raw = span / kTargetTicks;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * mag) return m * mag;
  return 10 * mag;
}

struct Axis {
  double lo = 0, hi = 1, step = 0.2;
};

Axis fit_axis(double lo, double hi) {
  if (!(hi > lo)) hi = lo + 1;
  Axis a;
  a.step = nice_step(hi - lo);
  a.lo = std::floor(lo / a.step) * a.step;
  a.hi = std::ceil(hi / a.step) * a.step;
  return a;
}

}  // namespace

std::string svg_plot(const PlotSpec& spec) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, yhi = 0;
  for (const PlotSeries& s : spec.series) {
    assert(s.x.size() == s.y.size());
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]);
      xhi = std::max(xhi, s.x[i]);
      yhi = std::max(yhi, s.y[i]);
    }
  }
  if (!std::isfinite(xlo)) xlo = 0, xhi = 1;
  const Axis ax = fit_axis(std::min(xlo, 0.0), xhi), ay = fit_axis(0, yhi);
  // The legend's column fits its longest label (sans-serif 12 px: about kCharWidth a
  // character): the canvas grows instead of the labels running off it.
  std::size_t longest = 0;
  for (const PlotSeries& s : spec.series) longest = std::max(longest, s.label.size());
  const double legend = std::max(kMarginRight, kLegendSwatch + kCharWidth * double(longest));
  const double w = std::max(double(spec.width), kMarginLeft + kMinPlotWidth + legend);
  const double h = spec.height;
  const double pw = w - kMarginLeft - legend, ph = h - kMarginTop - kMarginBottom;
  auto px = [&](double x) { return kMarginLeft + (x - ax.lo) / (ax.hi - ax.lo) * pw; };
  auto py = [&](double y) { return kMarginTop + ph - (y - ay.lo) / (ay.hi - ay.lo) * ph; };

  std::string o;
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(w) + "\" height=\"" + num(h) +
       "\" viewBox=\"0 0 " + num(w) + " " + num(h) +
       "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  o += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o += "<text x=\"" + num(w / 2) + "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" +
       escape(spec.title) + "</text>\n";
  // Grid and ticks.
  for (double v = ax.lo; v <= ax.hi + ax.step / 2; v += ax.step) {
    o += "<line x1=\"" + num(px(v)) + "\" y1=\"" + num(kMarginTop) + "\" x2=\"" + num(px(v)) +
         "\" y2=\"" + num(kMarginTop + ph) + "\" stroke=\"#ddd\"/>\n";
    o += "<text x=\"" + num(px(v)) + "\" y=\"" + num(kMarginTop + ph + 16) +
         "\" text-anchor=\"middle\">" + tick_label(v) + "</text>\n";
  }
  for (double v = ay.lo; v <= ay.hi + ay.step / 2; v += ay.step) {
    o += "<line x1=\"" + num(kMarginLeft) + "\" y1=\"" + num(py(v)) + "\" x2=\"" +
         num(kMarginLeft + pw) + "\" y2=\"" + num(py(v)) + "\" stroke=\"#ddd\"/>\n";
    o += "<text x=\"" + num(kMarginLeft - 6) + "\" y=\"" + num(py(v) + 4) +
         "\" text-anchor=\"end\">" + tick_label(v) + "</text>\n";
  }
  o += "<rect x=\"" + num(kMarginLeft) + "\" y=\"" + num(kMarginTop) + "\" width=\"" + num(pw) +
       "\" height=\"" + num(ph) + "\" fill=\"none\" stroke=\"black\"/>\n";
  o += "<text x=\"" + num(kMarginLeft + pw / 2) + "\" y=\"" + num(h - 12) +
       "\" text-anchor=\"middle\">" + escape(spec.x_label) + "</text>\n";
  o += "<text transform=\"translate(18," + num(kMarginTop + ph / 2) +
       ") rotate(-90)\" text-anchor=\"middle\">" + escape(spec.y_label) + "</text>\n";
  // Series and legend.
  const std::size_t ncol = sizeof kColours / sizeof kColours[0];
  for (std::size_t k = 0; k < spec.series.size(); ++k) {
    const PlotSeries& s = spec.series[k];
    const std::string colour = kColours[k % ncol];
    if (s.lines && s.x.size() > 1) {
      o += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\" points=\"";
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
          o += num(px(s.x[i])) + "," + num(py(s.y[i])) + " ";
      o += "\"/>\n";
    }
    if (s.markers || s.x.size() == 1)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
          o += "<circle cx=\"" + num(px(s.x[i])) + "\" cy=\"" + num(py(s.y[i])) + "\" r=\"" +
               num(kMarkerRadius) + "\" fill=\"" + colour + "\"/>\n";
    const double ly = kMarginTop + 10 + 18 * double(k), lx = kMarginLeft + pw + 12;
    o += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 20) + "\" y2=\"" +
         num(ly) + "\" stroke=\"" + colour + "\" stroke-width=\"3\"/>\n";
    o += "<text x=\"" + num(lx + 26) + "\" y=\"" + num(ly + 4) + "\">" + escape(s.label) +
         "</text>\n";
  }
  o += "</svg>\n";
  return o;
}

void write_svg_plot(const PlotSpec& spec, const std::string& path) {
  write_file_atomically(path, svg_plot(spec));
}

}  // namespace tsp
