// The SVG plot writer: well-formed XML (pugixml), escaped text, one polyline per line series,
// markers where asked, points inside the plot frame.
#include "tsp/report/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <pugixml.hpp>
#include <string>

#include "support/paths.h"
#include "tsp/core/error.h"

namespace {

pugi::xml_document parse(const std::string& text) {
  pugi::xml_document doc;
  pugi::xml_parse_result r = doc.load_string(text.c_str());
  EXPECT_TRUE(r) << r.description();
  return doc;
}

tsp::PlotSpec spec() {
  tsp::PlotSpec s;
  s.title = "a <title> & \"quotes\"";
  s.x_label = "step";
  s.y_label = "ms";
  s.series.push_back({"line", {0, 1, 2, 3}, {10, 20, 15, 30}});
  s.series.push_back({"dots", {0.5, 2.5}, {5, 25}, false, true});
  return s;
}

TEST(SvgPlot, IsWellFormedWithEscapedText) {
  pugi::xml_document doc = parse(tsp::svg_plot(spec()));
  pugi::xml_node svg = doc.child("svg");
  ASSERT_TRUE(svg);
  bool found_title = false;
  for (pugi::xml_node t : svg.children("text"))
    if (std::string(t.child_value()) == "a <title> & \"quotes\"") found_title = true;
  EXPECT_TRUE(found_title);
}

TEST(SvgPlot, DrawsSeriesInsideTheFrame) {
  tsp::PlotSpec s = spec();
  pugi::xml_document doc = parse(tsp::svg_plot(s));
  pugi::xml_node svg = doc.child("svg");
  int polylines = 0, circles = 0;
  for (pugi::xml_node n : svg.children("polyline")) {
    ++polylines;
    // Four points, each "x,y".
    std::string pts = n.attribute("points").value();
    int pairs = 0;
    for (char c : pts) pairs += c == ',';
    EXPECT_EQ(pairs, 4);
  }
  EXPECT_EQ(polylines, 1);
  pugi::xml_node frame;
  for (pugi::xml_node r : svg.children("rect"))
    if (std::string(r.attribute("fill").value()) == "none") frame = r;
  ASSERT_TRUE(frame);
  const double fx = frame.attribute("x").as_double(), fy = frame.attribute("y").as_double();
  const double fw = frame.attribute("width").as_double(),
               fh = frame.attribute("height").as_double();
  for (pugi::xml_node c : svg.children("circle")) {
    ++circles;
    const double cx = c.attribute("cx").as_double(), cy = c.attribute("cy").as_double();
    EXPECT_GE(cx, fx);
    EXPECT_LE(cx, fx + fw);
    EXPECT_GE(cy, fy);
    EXPECT_LE(cy, fy + fh);
  }
  EXPECT_EQ(circles, 2);
}

TEST(SvgPlot, LargerValuesAreHigherUp) {
  tsp::PlotSpec s;
  s.series.push_back({"p", {0, 1}, {1, 100}, false, true});
  pugi::xml_document doc = parse(tsp::svg_plot(s));
  std::vector<double> cy;
  for (pugi::xml_node c : doc.child("svg").children("circle"))
    cy.push_back(c.attribute("cy").as_double());
  ASSERT_EQ(cy.size(), 2u);
  EXPECT_GT(cy[0], cy[1]);  // SVG y grows downwards
}

TEST(SvgPlot, EmptyPlotIsStillValid) {
  tsp::PlotSpec s;
  s.title = "nothing yet";
  pugi::xml_document doc = parse(tsp::svg_plot(s));
  pugi::xml_node svg = doc.child("svg");
  ASSERT_TRUE(svg);
  // The frame, the axes' ticks and the title are drawn; no data.
  EXPECT_FALSE(svg.child("polyline"));
  EXPECT_FALSE(svg.child("circle"));
  int frames = 0, titles = 0, lines = 0;
  for (pugi::xml_node r : svg.children("rect"))
    frames += std::string(r.attribute("fill").value()) == "none";
  for (pugi::xml_node t : svg.children("text")) titles += std::string(t.child_value()) == "nothing yet";
  for (pugi::xml_node l : svg.children("line")) {
    ++lines;
    for (const char* a : {"x1", "y1", "x2", "y2"}) EXPECT_TRUE(std::isfinite(l.attribute(a).as_double()));
  }
  EXPECT_EQ(frames, 1);
  EXPECT_EQ(titles, 1);
  EXPECT_GT(lines, 0);  // grid lines of the default [0, 1] axes
}

TEST(SvgPlot, WritesAFileAndRejectsAMissingDirectory) {
  auto dir = tsptest::temp_dir();
  tsp::write_svg_plot(spec(), (dir / "p.svg").string());
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file((dir / "p.svg").c_str()));
  EXPECT_THROW(tsp::write_svg_plot(spec(), (dir / "no" / "p.svg").string()), tsp::IoError);
}

}  // namespace

namespace {

TEST(SvgPlot, LegendLabelsFitTheCanvas) {
  // A long label (bench's "tsp perceptual, cache off" and longer) widens the canvas so that
  // its estimated extent (7.2 px a character) ends inside it.
  tsp::PlotSpec s = spec();
  const std::string label = "tsp perceptual, cache off, spacing 0.25, preintegrated";
  s.series.push_back({label, {1, 2}, {3, 4}});
  pugi::xml_document doc = parse(tsp::svg_plot(s));
  pugi::xml_node svg = doc.child("svg");
  const double width = svg.attribute("width").as_double();
  for (pugi::xml_node t : svg.children("text"))
    if (std::string(t.child_value()) == label)
      EXPECT_LE(t.attribute("x").as_double() + 7.2 * double(label.size()), width + 1e-9);
  EXPECT_GT(width, 720);  // grew beyond the default
  EXPECT_NE(tsp::svg_plot(spec()).find("width=\"720.00\""), std::string::npos);  // short labels: as asked
}

}  // namespace
