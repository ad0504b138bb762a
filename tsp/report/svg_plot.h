// A small SVG line/scatter plot writer for the bench figures (no plotting dependency).
#pragma once
#include <string>
#include <vector>

namespace tsp {

/// One series of a plot: points (x[i], y[i]) drawn as a polyline and/or markers.
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  bool lines = true;
  bool markers = false;
};

/// A whole plot: title, axis labels, series; axes fitted to the data (y from 0).
struct PlotSpec {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  int width = 720, height = 440;
};

/// The plot as a standalone SVG document (text is XML-escaped). Asserts x and y sizes match.
std::string svg_plot(const PlotSpec& spec);

/// Writes svg_plot(spec) to path atomically. Throws IoError.
void write_svg_plot(const PlotSpec& spec, const std::string& path);

}  // namespace tsp
