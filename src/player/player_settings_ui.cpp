// The player's expert knobs, in the side panel's collapsed "Rendering (expert)" section: the
// metric, the tolerances with what they buy, the render settings table's widgets, the playing
// quality target, the LOD cut and the caches (docs/player.md "Panels").
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "player/player_app.h"
#include "player/player_ui.h"
#include "player/ui_items.h"
#include "render/settings_table.h"

namespace tspplayer {

namespace {

constexpr const char* kMetricNames[] = {"scalar", "reference", "approximate", "perceptual"};
// What a tolerance measures, per metric (tsp::Metric order; docs/metrics.md): short under the
// sliders, in full in their tooltip.
constexpr const char* kToleranceUnits[] = {
    "units: sigma/mean of the values", "units: colour dev./colour, exact",
    "units: colour dev./colour, estimated", "units: L*u*v* dev./100 per colour"};
constexpr const char* kToleranceHelp[] = {
    "coefficient of variation of the values (sigma/mean); 0 = exact",
    "colour deviation over colour magnitude (eq. 7), computed over every voxel; 0 = exact",
    "colour deviation over colour magnitude (eq. 7), estimated; 0 = exact",
    "L*u*v* deviation / 100 over colour magnitude; 0 = exact"};
// Units longer than this go in the widget's tooltip, not its label (the panel is narrow).
constexpr std::size_t kMaxUnitInLabel = 6;
// Frames of the window's history averaged for the "last frames" readout.
constexpr std::size_t kReadoutFrames = 10;

// One widget for a row of the render settings table: a log slider over its panel range (Ctrl +
// click types any value the table accepts), a checkbox or a combo; a change is a `setting`
// command, as a script line makes.
void setting_widget(PlayerApp& app, const tspgl::SettingSpec& spec) {
  const std::string name(spec.name), now = tspgl::get_setting(app.state().settings, spec);
  std::string label = name;
  for (char& c : label)
    if (c == '-') c = ' ';
  std::string next;
  switch (spec.kind) {
    case tspgl::SettingKind::number: {
      if (!spec.unit.empty() && spec.unit.size() <= kMaxUnitInLabel)
        label += " (" + std::string(spec.unit) + ")";
      float v = float(std::strtod(now.c_str(), nullptr));
      const bool off_at_zero = spec.lo == 0;
      const std::string shown = fit_label(label.c_str());
      if (ImGui::SliderFloat(shown.c_str(), &v, float(spec.ui_lo), float(spec.ui_hi),
                             off_at_zero && v == 0 ? "off" : "%.3g",
                             ImGuiSliderFlags_Logarithmic)) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.9g",
                      std::clamp(double(v), spec.lo, std::min(spec.hi, 1e300)));
        next = buf;
      }
      note_item(shown.c_str());
      break;
    }
    case tspgl::SettingKind::toggle: {
      bool on = now == "on";
      if (ImGui::Checkbox(label.c_str(), &on)) next = on ? "on" : "off";
      note_item(label.c_str());
      break;
    }
    case tspgl::SettingKind::choice: {
      int k = 0;
      std::string items;  // ImGui's zero-separated list
      for (std::size_t i = 0; i < spec.choices.size(); ++i) {
        if (spec.choices[i] == now) k = int(i);
        items += std::string(spec.choices[i]) + '\0';
      }
      const std::string shown = fit_label(label.c_str());
      if (ImGui::Combo(shown.c_str(), &k, items.c_str())) next = std::string(spec.choices[std::size_t(k)]);
      note_item(shown.c_str());
      break;
    }
  }
  if (ImGui::IsItemHovered()) {  // the table's help, as render --help says it
    const std::string help = std::string(spec.help) + (spec.unit.empty() ? "" : "; in ") +
                             std::string(spec.unit);
    tooltip(help.c_str());
  }
  if (next.empty()) return;
  app.push(cmd::SetSetting{name, next});
}

// The widgets of every row of group g but the tolerances (their sliders span the metric's range).
void setting_widgets(PlayerApp& app, tspgl::SettingGroup g) {
  for (const tspgl::SettingSpec& spec : tspgl::settings_table())
    if (spec.group == g && spec.name != "spatial-tol" && spec.name != "temporal-tol")
      setting_widget(app, spec);
}

// The tolerance sliders, their units and what they buy: the last frames' time, and the frame
// time and mean dE against tolerance 0 measured when they changed. Always the same lines, so
// nothing below moves when a readout arrives.
void tolerance_rows(PlayerApp& app) {
  float s = float(app.state().settings.tol.spatial), t = float(app.state().settings.tol.temporal);
  std::string label = fit_label("spatial tol");
  bool changed =
      ImGui::SliderFloat(label.c_str(), &s, 0.f, app.tol_max, "%.4g", ImGuiSliderFlags_Logarithmic);
  note_item(label.c_str());
  const char* help = kToleranceHelp[int(app.state().metric)];
  if (ImGui::IsItemHovered()) tooltip(help);
  bool done = ImGui::IsItemDeactivatedAfterEdit();
  label = fit_label("temporal tol");
  changed |= ImGui::SliderFloat(label.c_str(), &t, 0.f, app.tol_max, "%.4g",
                                ImGuiSliderFlags_Logarithmic);
  note_item(label.c_str());
  if (ImGui::IsItemHovered()) tooltip(help);
  done |= ImGui::IsItemDeactivatedAfterEdit();
  // Frames follow the slider at once; unreachable textures are dropped when it is released.
  if (changed || done) app.push(cmd::SetTolerance{double(s), double(t), done});
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextUnformatted(kToleranceUnits[int(app.state().metric)]);
  if (ImGui::IsItemHovered()) tooltip(help);
  ImGui::PopStyleColor();
  double sum = 0;
  std::size_t n = 0;
  for (auto it = app.history.rbegin(); it != app.history.rend() && n < kReadoutFrames; ++it, ++n)
    sum += it->ms;
  const PlayerApp::ToleranceReadout& r = app.tol_readout;
  if (r.at.spatial >= 0)
    ImGui::Text("buys: %.1f ms (exact %.1f), dE %.2f", r.ms, r.exact_ms, r.mean_de);
  else
    ImGui::TextUnformatted("buys: (measured when a tolerance changes)");
  if (ImGui::IsItemHovered())
    tooltip("The shown step and view drawn off-screen (at most 320 x 200) at these tolerances "
            "and at 0, when they changed: the frame time of each and the mean dE between the "
            "two pictures.");
  ImGui::Text("last %zu frames: %.1f ms", n, n ? sum / double(n) : 0.0);
}

void lod_rows(PlayerApp& app) {
  // Level of detail: the cut holds the frame rate while anything changes, full quality when idle.
  bool lod = app.state().lod_on;
  if (ImGui::Checkbox("level of detail", &lod))
    app.push(cmd::SetLod{lod});
  note_item("level of detail");
  // In the row's second half, as the button pairs: a label ending 8 pixels before the next
  // checkbox read as running into it.
  ImGui::SameLine(ImGui::GetCursorStartPos().x + (ImGui::GetContentRegionMax().x - ImGui::GetCursorStartPos().x) / 2);
  if (bool cut = app.state().show_cut; ImGui::Checkbox("show cut (L)", &cut))
    app.push(cmd::ShowCut{cut});
  note_item("show cut (L)");
  const std::string fps_label = fit_label("target fps");
  if (float fps = app.state().target_fps;
      ImGui::SliderFloat(fps_label.c_str(), &fps, 5.f, 120.f, "%.0f")) {
    app.push(cmd::SetTargetFps{std::clamp(double(fps), 1.0, kMaxTargetFps)});
  }
  note_item(fps_label.c_str());
  if (bool on = app.state().splat_fallback; ImGui::Checkbox("splats when the coarsest cut is slow", &on))
    app.push(cmd::SplatFallback{on});
  note_item("splats when the coarsest cut is slow");
  // How the cut is chosen: by error against the target, or by LaMar's selection filters.
  static const char* const kFilters[] = {"error (target fps)", "distance from the eye",
                                         "field of view"};
  int kind = int(app.state().lod_filter.kind);
  float k = float(app.state().lod_filter.scale);
  const std::string by = fit_label("cut by");
  const bool picked = ImGui::Combo(by.c_str(), &kind, kFilters, 3);
  note_item(by.c_str());
  if (ImGui::IsItemHovered())
    tooltip("LaMar's filters: a tile is drawn whole when the eye is more than K diagonals away "
            "(distance) or when it subtends less than half the field of view over K (fov; "
            "outside the view: not refined)");
  bool scaled = false;
  if (kind != 0) {
    const std::string kl = fit_label("K");
    scaled = ImGui::SliderFloat(kl.c_str(), &k, 0.25f, 8.f, "%.2f", ImGuiSliderFlags_Logarithmic);
    note_item(kl.c_str());
  }
  if (picked || scaled) {
    const char* const names[] = {"error", "distance", "fov"};
    char text[64];
    std::snprintf(text, sizeof text, "%s:%g", names[kind], double(k));
    app.push(cmd::SetLodFilter{kind == 0 ? "error" : text});
  }
}

}  // namespace

void settings_section(PlayerApp& app) {
  const std::string metric_label = fit_label("metric");
  int m = int(app.state().metric);
  if (ImGui::Combo(metric_label.c_str(), &m, kMetricNames, IM_ARRAYSIZE(kMetricNames)))
    app.push(cmd::SetMetric{tsp::Metric(m)});
  note_item(metric_label.c_str());
  if (ImGui::IsItemHovered())
    tooltip(app.state().metric == tsp::Metric::reference
                ? "reference: every voxel is read; computed in full on each TF change (the "
                  "window waits)"
                : "live: only the nodes a frame visits are recomputed after a TF edit");
  tolerance_rows(app);
  setting_widgets(app, tspgl::SettingGroup::quality);
  setting_widgets(app, tspgl::SettingGroup::compositing);
  if (app.expand_sections != 0) ImGui::SetNextItemOpen(app.expand_sections > 0, ImGuiCond_Always);
  if (ImGui::TreeNode("diagnostics")) {
    if (ImGui::IsItemHovered()) tooltip("the paper's rules, our optimisations off");
    setting_widgets(app, tspgl::SettingGroup::diagnostics);
    ImGui::TreePop();
  }
  // While playing, the quality target picks the rung of the tuned ladder (the knobs above made
  // cheaper: spacing, render scale, LOD level) that fits the speed within the target.
  float quality = app.state().quality;
  const std::string q_label = fit_label("playing quality (mean dE)");
  ImGui::SliderFloat(q_label.c_str(), &quality, 0.f, 10.f, quality > 0 ? "%.2f" : "off");
  note_item(q_label.c_str());
  if (ImGui::IsItemHovered())
    tooltip("while playing: mean dE against the full-quality picture (paused: always full "
            "quality); off: the LOD cut holds the frame rate");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    app.push(cmd::SetQuality{quality});
  }
  ImGui::BeginDisabled(app.state().quality <= 0);
  ImGui::TextUnformatted("while playing, keep:");
  ImGui::SameLine();
  if (ImGui::RadioButton("quality", app.state().keep_quality))
    app.push(cmd::KeepQuality{true});
  note_item("quality");
  ImGui::SameLine();
  if (ImGui::RadioButton("rate", !app.state().keep_quality))
    app.push(cmd::KeepQuality{false});
  note_item("rate");
  ImGui::EndDisabled();
  lod_rows(app);
  if (app.expand_sections != 0) ImGui::SetNextItemOpen(app.expand_sections > 0, ImGuiCond_Always);
  if (ImGui::TreeNode("caches and uploads")) {
    bool cache = app.state().cache_on;
    if (ImGui::Checkbox("texture cache", &cache))
      app.push(cmd::SetCache{cache});
    note_item("texture cache");
    ImGui::SameLine();
    if (bool on = app.state().prefetch_on; ImGui::Checkbox("prefetch", &on))
      app.push(cmd::SetPrefetch{on});
    note_item("prefetch");
    setting_widgets(app, tspgl::SettingGroup::memory);
    static double budget = -1;
    if (budget < 0) budget = app.state().texture_budget_mb;
    const std::string b_label = fit_label("budget MiB");
    ImGui::InputDouble(b_label.c_str(), &budget, 16, 128, "%.0f");
    note_item(b_label.c_str());
    if (ImGui::IsItemDeactivatedAfterEdit()) app.push(cmd::SetCache{app.state().cache_on, budget});
    ImGui::TreePop();
  }
}

}  // namespace tspplayer
