// The player's transfer-function editor: the value histogram with the opacity curve over it and a
// handle per control point (drag, add, remove), the point list, presets and load/save
// (docs/player.md "Transfer function").
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "player/player_app.h"
#include "player/player_ui.h"
#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

namespace {

constexpr float kHistogramHeight = 80.f;
constexpr float kHandleRadius = 5.f;

}  // namespace

void tf_section(PlayerApp& app) {
  // Histogram (log counts) with the opacity curve drawn over it.
  const auto& hist = app.file->metadata().histogram;
  std::vector<float> logh;
  for (std::uint64_t c : hist) logh.push_back(std::log1p(float(c)));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const tsp::ValueRange d = app.tf.domain();
  const bool log_axis = app.state.log_opacity;
  // Opacity a at its height on the canvas (0 at the bottom).
  auto y_of = [&](double a) {
    return origin.y + kHistogramHeight * float(1 - opacity_to_axis(a, log_axis));
  };
  // Bars drawn by hand, not ImGui::PlotHistogram: that is an item whose hover (its tooltip)
  // would take the clicks meant for the handles below; and each bin sits at its values on the
  // TF domain's scale (the histogram covers the quantization range), so bars and curve line up.
  {
    const tsp::ValueRange q = app.file->tree().value_range();
    float top = 0;
    for (float v : logh) top = std::max(top, v);
    const double dspan = d.hi > d.lo ? d.hi - d.lo : 1.0;
    const double bin = (q.hi - q.lo) / double(logh.size());
    dl->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + kHistogramHeight),
                      ImGui::GetColorU32(ImGuiCol_FrameBg));
    for (std::size_t i = 0; i < logh.size() && top > 0; ++i) {
      const double v0 = q.lo + bin * double(i), v1 = v0 + bin;
      const float x0 = std::max(origin.x, origin.x + width * float((v0 - d.lo) / dspan));
      const float x1 = std::min(origin.x + width, origin.x + width * float((v1 - d.lo) / dspan));
      if (x1 <= x0) continue;
      dl->AddRectFilled(ImVec2(x0, origin.y + kHistogramHeight * (1 - logh[i] / top)),
                        ImVec2(std::max(x1, x0 + 1), origin.y + kHistogramHeight),
                        ImGui::GetColorU32(ImGuiCol_PlotHistogram));
    }
    if (log_axis)  // decade lines of the log opacity axis (1e-3, 1e-2, 1e-1)
      for (double a = 1e-3; a < 1; a *= 10)
        dl->AddLine(ImVec2(origin.x, y_of(a)), ImVec2(origin.x + width, y_of(a)),
                    IM_COL32(255, 255, 255, 40));
  }
  const int n = app.tf.size();
  for (int j = 1; j < n; ++j) {
    const tsp::Rgba a = app.tf.entry(j - 1), b = app.tf.entry(j);
    // Entries at their values, so the curve and the handles share the TF domain's scale.
    const float x0 = origin.x + width * float((app.tf.entry_value(j - 1) - d.lo) / (d.hi - d.lo));
    const float x1 = origin.x + width * float((app.tf.entry_value(j) - d.lo) / (d.hi - d.lo));
    dl->AddLine(ImVec2(x0, y_of(a.a)), ImVec2(x1, y_of(b.a)),
                ImGui::ColorConvertFloat4ToU32(ImVec4(b.r, b.g, b.b, 1)), 2.f);
  }
  bool edited = false;
  int remove = -1;
  // Handles on the curve: drag to move a point (value, opacity), double-click empty space to
  // add one, right-click a point to remove it.
  ImGui::SetCursorScreenPos(origin);
  ImGui::InvisibleButton("##canvas", ImVec2(width, kHistogramHeight));
  app.trace_tf_canvas(origin.x, origin.y, width, kHistogramHeight);
  const double span = d.hi > d.lo ? d.hi - d.lo : 1.0;
  auto screen = [&](const tsp::TfPoint& p) {
    return ImVec2(origin.x + width * float((p.x - d.lo) / span), y_of(p.c.a));
  };
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const double mouse_x = std::clamp(d.lo + double(mouse.x - origin.x) / width * span, d.lo, d.hi);
  const float mouse_a =
      float(axis_to_opacity(1.0 - double(mouse.y - origin.y) / kHistogramHeight, log_axis));
  // The handle nearest a screen point, within reach (−1: none).
  auto handle_at = [&](ImVec2 at) {
    int found = -1;
    float best = kHandleRadius * kHandleRadius * 4;
    for (std::size_t i = 0; i < app.tf_points.size(); ++i) {
      const ImVec2 h = screen(app.tf_points[i]);
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

  if (ImGui::IsItemActive() && dragging >= 0 && dragging < int(app.tf_points.size()) &&
      (ImGui::GetIO().MouseDelta.x != 0 || ImGui::GetIO().MouseDelta.y != 0)) {
    app.tf_points[std::size_t(dragging)].x = mouse_x;
    app.tf_points[std::size_t(dragging)].c.a = mouse_a;
    edited = true;
  }
  if (ImGui::IsItemDeactivated()) dragging = -1;
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0) && hovered < 0) {
    tsp::Rgba c = app.tf.lookup(mouse_x);
    c.a = mouse_a;
    app.tf_points.push_back({mouse_x, c});
    edited = true;
  }
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(1) && hovered >= 0 &&
      app.tf_points.size() > 2)
    remove = hovered;
  for (std::size_t i = 0; i < app.tf_points.size(); ++i) {
    const tsp::TfPoint& p = app.tf_points[i];
    const ImVec2 h = screen(p);
    dl->AddCircleFilled(h, kHandleRadius,
                        ImGui::ColorConvertFloat4ToU32(ImVec4(p.c.r, p.c.g, p.c.b, 1)));
    dl->AddCircle(h, kHandleRadius,
                  int(i) == hovered ? IM_COL32(255, 255, 0, 255) : IM_COL32_WHITE);
  }
  ImGui::Text("domain %.4g .. %.4g", d.lo, d.hi);
  ImGui::SameLine();
  ImGui::Checkbox("log opacity", &app.state.log_opacity);
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("drag a point; double-click adds, right-click removes");
  ImGui::PopStyleColor();
  for (std::size_t i = 0; i < app.tf_points.size(); ++i) {
    tsp::TfPoint& p = app.tf_points[i];
    ImGui::PushID(int(i));
    float x = float(p.x);
    ImGui::SetNextItemWidth(100);
    if (ImGui::DragFloat("##x", &x, float(d.hi - d.lo) / 500.f, float(d.lo), float(d.hi), "%.4g")) {
      p.x = std::clamp(double(x), d.lo, d.hi);
      edited = true;
    }
    ImGui::SameLine();
    float c[4] = {p.c.r, p.c.g, p.c.b, p.c.a};
    if (ImGui::ColorEdit4("##c", c, ImGuiColorEditFlags_AlphaBar | ImGuiColorEditFlags_NoInputs)) {
      p.c = {c[0], c[1], c[2], c[3]};
      edited = true;
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(110);
    // Opacity near zero is edited on a log scale when the axis is (VAPOR users ask for it).
    if (ImGui::SliderFloat("##a", &c[3], log_axis ? float(kLogOpacityFloor) : 0.f, 1.f,
                           log_axis ? "a %.2e" : "a %.3f",
                           log_axis ? ImGuiSliderFlags_Logarithmic : 0)) {
      p.c.a = c[3];
      edited = true;
    }
    ImGui::SameLine();
    if (app.tf_points.size() > 2 && ImGui::SmallButton("x")) remove = int(i);
    ImGui::PopID();
  }
  if (remove >= 0) {
    app.tf_points.erase(app.tf_points.begin() + remove);
    edited = true;
  }
  if (ImGui::Button("add point")) {
    app.tf_points.push_back({(d.lo + d.hi) / 2, app.tf.lookup((d.lo + d.hi) / 2)});
    edited = true;
  }
  if (edited) app.apply_tf_points();  // lazy metric: only touched nodes recompute next frame

  // The combo names the map in use and applies a preset when one is chosen (over the map's
  // present domain).
  ImGui::SetNextItemWidth(120);
  if (ImGui::BeginCombo("##preset", app.tf_label.c_str())) {
    for (const std::string& name : tsp::preset_names())
      if (ImGui::Selectable(name.c_str(), name == app.tf_label)) {
        const tsp::ValueHistogram histogram = tsp::histogram_of(*app.file);
        app.set_tf(tsp::preset_transfer_function(name, d, app.tf.size(), &histogram), true);
        app.tf_label = name;
      }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the colour map in use; choose a preset to apply it");
  ImGui::SameLine();
  if (ImGui::Button("fit to data")) {  // the map as it is, stretched over the data's range
    app.set_tf(tsp::rescaled(app.tf, d), true);
    app.status = "transfer function stretched over the data range";
  }
  ImGui::SameLine();
  if (ImGui::Button("fit to bulk")) {  // over the 1st to 99th percentile of the samples
    ScriptAction fit;
    fit.kind = ScriptAction::Kind::tf_range;
    fit.text = "histogram";
    app.command(fit);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Stretch the map over where the data is: the 1st to 99th percentile of\n"
                      "every sample (tf-range histogram)");
  if (ImGui::Button("fit to step")) {  // over the range of the step shown
    ScriptAction fit;
    fit.kind = ScriptAction::Kind::tf_range;
    fit.text = "step";
    app.command(fit);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Stretch the map over the range of the step shown (tf-range step)");
  ImGui::SameLine();
  if (ImGui::Button("fit to view")) {  // over what the view shows of the step
    ScriptAction fit;
    fit.kind = ScriptAction::Kind::tf_range;
    fit.text = "visible";
    app.command(fit);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Stretch the map over the values of the bricks in view and inside the\n"
                      "clip probes, at the step shown (tf-range visible)");

  static char path[512] = "";
  if (path[0] == 0) std::snprintf(path, sizeof path, "%s", app.tf_path.c_str());
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##path", path, sizeof path);
  app.tf_path = path;
  try {
    if (ImGui::Button("load")) {
      const tsp::ValueHistogram histogram = tsp::histogram_of(*app.file);
      app.set_tf(tsp::transfer_function_from_arg(app.tf_path, d, app.tf.size(), {}, &histogram),
                 true);
      app.tf_label = tf_label_of(app.tf_path);
      const std::string w = tsp::tf_range_warning(app.tf, app.file->metadata().data_range);
      app.status = w.empty() ? "loaded " + app.tf_path : "loaded " + app.tf_path + "; " + w;
    }
  } catch (const tsp::Error& e) {
    app.status = e.what();  // shown in the settings panel; the player keeps running
  }
  ImGui::SameLine();
  if (ImGui::Button("save as")) app.save_tf_as(app.tf_path);
}

}  // namespace tspplayer
