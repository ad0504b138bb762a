// The player's transfer-function editor: the value histogram with the opacity curve over it and a
// handle per control point (drag, add, remove), the point list, presets and load/save
// (docs/player.md "Transfer function").
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "player/player_app.h"
#include "player/player_ui.h"
#include "player/tf_histogram.h"
#include "player/ui_items.h"
#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

namespace {

constexpr float kHistogramHeight = 80.f;
constexpr float kHandleRadius = 5.f;
// Pixels per histogram bar, and most bars.
constexpr float kBinPixels = 3.f;
constexpr int kMaxBins = 128;

// The colour range as text, LO:HI: typed and Enter stretches the map over it (the script's
// `tf-range LO:HI`); it shows the domain in use whenever it is not being edited.
void domain_row(PlayerApp& app, const tsp::ValueRange& d) {
  static char text[96] = "";
  static bool editing = false;
  if (!editing) {  // (float noise at an end that is zero shows as 0, not -1.6e-26)
    const double tiny = 1e-9 * std::max(std::fabs(d.lo), std::fabs(d.hi));
    std::snprintf(text, sizeof text, "%.6g:%.6g", std::fabs(d.lo) < tiny ? 0.0 : d.lo,
                  std::fabs(d.hi) < tiny ? 0.0 : d.hi);
  }
  const std::string label = fit_label("range LO:HI");
  const bool entered =
      ImGui::InputText(label.c_str(), text, sizeof text,
                       ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  note_item(label.c_str());
  editing = ImGui::IsItemActive();
  if (ImGui::IsItemHovered())
    tooltip(
        "The colour range the map is stretched over: type LO:HI and press Enter "
        "(tf-range LO:HI)");
  if (!entered) return;
  editing = false;
  app.push(cmd::StretchTf{text});  // a bad range: the status area says why
}

// The histogram under the curve, counted again only when the domain, the file or the bins
// change (a step's count reads bricks; the step it counted stays until then).
const EditorHistogram& histogram_for(PlayerApp& app, const tsp::ValueRange& d, float width) {
  return app.editor_histogram(d, std::clamp(int(width / kBinPixels), 8, kMaxBins));
}

// The canvas the histogram, the curve and the handles share: its place on screen, the TF's
// domain across it and the opacity axis up it.
struct Canvas {
  ImVec2 origin;
  float width;
  tsp::ValueRange d;
  bool log_axis;
  ImDrawList* dl;
  /// Opacity a at its height on the canvas (0 at the bottom).
  float y_of(double a) const {
    return origin.y + kHistogramHeight * float(1 - opacity_to_axis(a, log_axis));
  }
};

// The histogram under the curve. Bars drawn by hand, not ImGui::PlotHistogram: that is an item
// whose hover (its tooltip) would take the clicks meant for the handles. The bins span the TF's
// domain, so bars and curve line up; enough of them to show the data (tf_histogram.h), log
// counts.
void draw_histogram(PlayerApp& app, const Canvas& cv) {
  const auto& [origin, width, d, log_axis, dl] = cv;
  auto y_of = [&](double a) { return cv.y_of(a); };
  const EditorHistogram& hist = histogram_for(app, d, width);
  std::vector<float> logh;
  float top = 0;
  for (double c : hist.counts) {
    logh.push_back(std::log1p(float(c)));
    top = std::max(top, logh.back());
  }
  dl->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + kHistogramHeight),
                    ImGui::GetColorU32(ImGuiCol_FrameBg));
  const float bw = width / float(std::max<std::size_t>(1, logh.size()));
  for (std::size_t i = 0; i < logh.size() && top > 0; ++i) {
    if (logh[i] <= 0) continue;
    const float x0 = origin.x + bw * float(i);
    dl->AddRectFilled(ImVec2(x0, origin.y + kHistogramHeight * (1 - logh[i] / top)),
                      ImVec2(std::max(x0 + bw, x0 + 1), origin.y + kHistogramHeight),
                      ImGui::GetColorU32(ImGuiCol_PlotHistogram));
  }
  if (log_axis)  // decade lines of the log opacity axis (1e-3, 1e-2, 1e-1)
    for (double a = 1e-3; a < 1; a *= 10)
      dl->AddLine(ImVec2(origin.x, y_of(a)), ImVec2(origin.x + width, y_of(a)),
                  IM_COL32(255, 255, 255, 40));
}

// The TF's opacity curve, each segment in its entry's colour, entries at their values.
void draw_curve(const PlayerApp& app, const Canvas& cv) {
  const auto& [origin, width, d, log_axis, dl] = cv;
  auto y_of = [&](double a) { return cv.y_of(a); };
  const int n = app.tf.size();
  for (int j = 1; j < n; ++j) {
    const tsp::Rgba a = app.tf.entry(j - 1), b = app.tf.entry(j);
    // Entries at their values, so the curve and the handles share the TF domain's scale.
    const float x0 = origin.x + width * float((app.tf.entry_value(j - 1) - d.lo) / (d.hi - d.lo));
    const float x1 = origin.x + width * float((app.tf.entry_value(j) - d.lo) / (d.hi - d.lo));
    dl->AddLine(ImVec2(x0, y_of(a.a)), ImVec2(x1, y_of(b.a)),
                ImGui::ColorConvertFloat4ToU32(ImVec4(b.r, b.g, b.b, 1)), 2.f);
  }
}

// The handles on the curve: drag to move a point (value, opacity), double-click empty space to
// add one, right-click a point to remove it. Each edit is a tf-point command (the script's).
void edit_handles(PlayerApp& app, const Canvas& cv) {
  const auto& [origin, width, d, log_axis, dl] = cv;
  auto y_of = [&](double a) { return cv.y_of(a); };
  const std::vector<tsp::TfPoint>& points = app.tf_points();
  ImGui::SetCursorScreenPos(origin);
  ImGui::InvisibleButton("##canvas", ImVec2(width, kHistogramHeight));
  app.trace_tf_canvas(origin.x, origin.y, width, kHistogramHeight);
  const double span = d.hi > d.lo ? d.hi - d.lo : 1.0;
  auto screen = [&](const tsp::TfPoint& p) {
    return ImVec2(origin.x + width * float((p.x - d.lo) / span), y_of(p.c.a));
  };
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const double mouse_x = std::clamp(d.lo + double(mouse.x - origin.x) / width * span, d.lo, d.hi);
  const double mouse_a = axis_to_opacity(1.0 - double(mouse.y - origin.y) / kHistogramHeight,
                                         log_axis);
  // The handle nearest a screen point, within reach (−1: none).
  auto handle_at = [&](ImVec2 at) {
    int found = -1;
    float best = kHandleRadius * kHandleRadius * 4;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const ImVec2 h = screen(points[i]);
      const float dist = (h.x - at.x) * (h.x - at.x) + (h.y - at.y) * (h.y - at.y);
      if (dist < best) {
        best = dist;
        found = int(i);
      }
    }
    return found;
  };
  const int hovered = handle_at(mouse);
  static int dragging = -1;
  // The handle under the press, not under the mouse now: on a slow frame the press and the
  // first moves arrive together, and the mouse has already left the handle.
  if (ImGui::IsItemActivated()) {
    const auto press = app.left_press();
    dragging = handle_at(ImVec2(press[0], press[1]));
  }
  if (ImGui::IsItemActive() && dragging >= 0 && dragging < int(points.size()) &&
      (ImGui::GetIO().MouseDelta.x != 0 || ImGui::GetIO().MouseDelta.y != 0))
    // (Kept between its neighbours: the handles keep their order, the curve between warps.)
    app.push(cmd::MoveTfPoint{dragging + 1, mouse_x, mouse_a});
  if (ImGui::IsItemDeactivated()) dragging = -1;
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0) && hovered < 0)
    app.push(cmd::AddTfPoint{mouse_x, mouse_a});
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(1) && hovered >= 0 && points.size() > 2)
    app.push(cmd::RemoveTfPoint{hovered + 1});
  for (std::size_t i = 0; i < points.size(); ++i) {
    const tsp::TfPoint& p = points[i];
    const ImVec2 h = screen(p);
    dl->AddCircleFilled(h, kHandleRadius,
                        ImGui::ColorConvertFloat4ToU32(ImVec4(p.c.r, p.c.g, p.c.b, 1)));
    dl->AddCircle(h, kHandleRadius,
                  int(i) == hovered ? IM_COL32(255, 255, 0, 255) : IM_COL32_WHITE);
  }
}

/// Width of the point list's opacity sliders (their value printed beside them).
constexpr float kOpacitySliderWidth = 76;

// The points as a list (value, colour, opacity; x removes one), under a tree node; each edit a
// tf-point command.
void point_list(PlayerApp& app, const tsp::ValueRange& d, bool log_axis) {
  const std::vector<tsp::TfPoint>& points = app.tf_points();
  if (app.expand_sections != 0) ImGui::SetNextItemOpen(app.expand_sections > 0, ImGuiCond_Always);
  char points_title[48];
  std::snprintf(points_title, sizeof points_title, "points (%zu)###points", points.size());
  const bool list = ImGui::TreeNode(points_title);
  for (std::size_t i = 0; list && i < points.size(); ++i) {
    const tsp::TfPoint& p = points[i];
    const int number = int(i) + 1;
    ImGui::PushID(int(i));
    float x = float(p.x);
    ImGui::SetNextItemWidth(100);
    if (ImGui::DragFloat("##x", &x, float(d.hi - d.lo) / 500.f, float(d.lo), float(d.hi), "%.4g"))
      app.push(cmd::MoveTfPoint{number, std::clamp(double(x), d.lo, d.hi), p.c.a});
    ImGui::SameLine();
    float c[4] = {p.c.r, p.c.g, p.c.b, p.c.a};
    if (ImGui::ColorEdit4("##c", c, ImGuiColorEditFlags_AlphaBar | ImGuiColorEditFlags_NoInputs))
      app.push(cmd::ColourTfPoint{number, {c[0], c[1], c[2], c[3]}});
    ImGui::SameLine();
    ImGui::SetNextItemWidth(kOpacitySliderWidth);
    // Opacity near zero is edited on a log scale when the axis is (VAPOR users ask for it). The
    // value is printed beside the slider: centred on it, its grab covered it (the eighth walk);
    // Ctrl+click still types one, in the slider.
    const char* format = log_axis ? "%.2e" : "%.3f";
    const bool typing = ImGui::TempInputIsActive(ImGui::GetID("##a"));
    if (!typing) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0, 0, 0, 0));
    const bool moved = ImGui::SliderFloat("##a", &c[3], log_axis ? float(kLogOpacityFloor) : 0.f,
                                          1.f, format, log_axis ? ImGuiSliderFlags_Logarithmic : 0);
    if (!typing) ImGui::PopStyleColor();
    if (moved) app.push(cmd::MoveTfPoint{number, p.x, std::clamp(double(c[3]), 0.0, 1.0)});
    if (ImGui::IsItemHovered()) tooltip("opacity (Ctrl+click to type one)");
    char value[32];
    std::snprintf(value, sizeof value, format, c[3]);
    const float value_x = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemInnerSpacing.x;
    ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::TextUnformatted(value);
    note_item(value);
    // (The remove button in one column, however wide the value.)
    ImGui::SameLine(value_x - ImGui::GetWindowPos().x + ImGui::GetScrollX() +
                    ImGui::CalcTextSize("0.00e-00").x + ImGui::GetStyle().ItemSpacing.x);
    if (points.size() > 2 && ImGui::SmallButton("x")) app.push(cmd::RemoveTfPoint{number});
    ImGui::PopID();
  }
  if (list) {
    if (ImGui::Button("add point")) app.push(cmd::AddTfPoint{(d.lo + d.hi) / 2, std::nullopt});
    note_item("add point", true);
    ImGui::TreePop();
  }
}

// The colour map combo (names the map in use, applies a chosen preset over the present domain)
// and the four fits of the colour range, two a row.
void colour_map_rows(PlayerApp& app) {
  const std::string preset = fit_label("colour map");
  if (ImGui::BeginCombo(preset.c_str(), app.tf_label.c_str())) {
    for (const std::string& name : tsp::preset_names())
      if (ImGui::Selectable(name.c_str(), name == app.tf_label))
        app.push(cmd::LoadTf{"preset:" + name, true});  // over the present range
    ImGui::EndCombo();
  }
  note_item(preset.c_str());
  if (ImGui::IsItemHovered()) tooltip("the colour map in use; choose a preset to apply it");
  // The colour range: four fits, two a row, each button half the row.
  const ImVec2 half((ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) / 2, 0);
  if (ImGui::Button("fit to data", half))  // the map as it is, stretched over the data's range
    app.push(cmd::StretchTf{"data"});
  note_item("fit to data", true);
  if (ImGui::IsItemHovered())
    tooltip("Stretch the map over the data's whole range (tf-range data)");
  ImGui::SameLine();
  if (ImGui::Button("fit to bulk", half)) {  // over the 1st to 99th percentile of the samples
    app.push(cmd::StretchTf{"bulk"});
  }
  note_item("fit to bulk", true);
  if (ImGui::IsItemHovered())
    tooltip(
        "Stretch the map over where the data is: the 1st to 99th percentile of every "
        "sample (tf-range bulk)");
  if (ImGui::Button("fit to step", half)) {  // over the range of the step shown
    app.push(cmd::StretchTf{"step"});
  }
  note_item("fit to step", true);
  if (ImGui::IsItemHovered())
    tooltip("Stretch the map over the range of the step shown (tf-range step)");
  ImGui::SameLine();
  if (ImGui::Button("fit to view", half)) {  // over what the view shows of the step
    app.push(cmd::StretchTf{"view"});
  }
  note_item("fit to view", true);
  if (ImGui::IsItemHovered())
    tooltip(
        "Stretch the map over the values of the bricks in view and inside the clip probes, "
        "at the step shown (tf-range view)");
}

// The TF file row: a path, load and save as.
void tf_file_row(PlayerApp& app) {
  static char path[512] = "";
  if (path[0] == 0) std::snprintf(path, sizeof path, "%s", tf_file_path().c_str());
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##path", path, sizeof path);
  tf_file_path() = path;
  const bool load = ImGui::Button("load");
  note_item("load", true);
  if (load) app.push(cmd::LoadTf{tf_file_path(), true});  // (errors: the status area)
  ImGui::SameLine();
  if (ImGui::Button("save as")) app.save_tf_as(tf_file_path());
  note_item("save as", true);
}

}  // namespace

std::string& tf_file_path() {
  static std::string path = "tf.json";
  return path;
}

void tf_section(PlayerApp& app) {
  // Histogram (log counts) with the opacity curve and its handles drawn over it.
  const Canvas cv{ImGui::GetCursorScreenPos(), ImGui::GetContentRegionAvail().x, app.tf.domain(),
                  app.state().log_opacity, ImGui::GetWindowDrawList()};
  const tsp::ValueRange d = cv.d;
  draw_histogram(app, cv);
  draw_curve(app, cv);
  edit_handles(app, cv);
  domain_row(app, d);
  if (bool on = app.state().log_opacity; ImGui::Checkbox("log opacity", &on))
    app.push(cmd::LogOpacity{on});
  note_item("log opacity");
  ImGui::SameLine();
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered())
    tooltip(
        "log opacity: the curve's height is the opacity on a log scale (1e-4 to 1, as the axis), so the "
        "faint opacities most maps need can be placed. Drag a point: the curve between its "
        "neighbours follows, keeping its detail. Double-click empty space to add a point, "
        "right-click a point to remove it.");
  point_list(app, d, cv.log_axis);
  colour_map_rows(app);
  tf_file_row(app);
}

}  // namespace tspplayer
