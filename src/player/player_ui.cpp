// The player's Dear ImGui panels: the layout (docked beside the volume, floating over it in a
// small window, or hidden), the settings, statistics and timeline sections, the controls
// overlay. Drawn after the volume each frame (docs/player.md).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "player/axis_scale_field.h"
#include "player/controls.h"
#include "player/player_app.h"
#include "player/player_ui.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {

// What playback draws and which of rate and quality gives, for the transport line.
std::string playback_text(const PlayerApp& app) {
  if (app.state.quality <= 0) return "(LOD cut holds the rate)";
  if (app.tuning() && app.tuned_rungs().empty()) return "(spacing x2, scale 0.5 while tuning)";
  if (!app.playing_rung()) return "";
  const tspgl::TunedRung& t = app.tuned_rungs()[std::size_t(app.rung_choice().index)];
  char text[160];
  if (!app.rung_choice().within_quality)
    std::snprintf(text, sizeof text, "%s, dE %.2f: keeping rate, quality gives", t.rung.name, t.mean_de);
  else if (!app.rung_choice().fits_rate)
    std::snprintf(text, sizeof text, "%s, dE %.2f: keeping quality, steps late", t.rung.name, t.mean_de);
  else
    std::snprintf(text, sizeof text, "%s, dE %.2f", t.rung.name, t.mean_de);
  return text;
}

constexpr float kHudPlotHeight = 60.f;
constexpr float kLabelWidth = 130.f;  // room for a settings label, pixels
constexpr float kReadyStripHeight = 5.f;  // the timeline's readiness marks, pixels
constexpr double kBytesPerMiB = 1 << 20;
// Playback showing fewer steps a second than this share of the speed says it plays slower.
constexpr double kSlowPlaybackShare = 0.9;
constexpr const char* kMetricNames[] = {"scalar", "reference", "approximate", "perceptual"};
// In tspgl::Compositing order.
constexpr const char* kClassNames[] = {"not rendered", "untextured", "reused texture",
                                       "new texture", "clipped"};
// What a tolerance measures, per metric (tsp::Metric order; docs/metrics.md).
constexpr const char* kToleranceUnits[] = {
    "units: coefficient of variation of the values (sigma/mean)",
    "units: colour deviation over colour magnitude (eq. 7), every voxel",
    "units: colour deviation over colour magnitude (eq. 7), estimated",
    "units: L*u*v* deviation / 100 over colour magnitude"};
// The docked panels: no title, fixed where the layout puts them, under any popup.
constexpr ImGuiWindowFlags kDockedFlags =
    ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
    ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
    ImGuiWindowFlags_NoBringToFrontOnFocus;

void place(const WindowRect& r) {
  ImGui::SetNextWindowPos(ImVec2(float(r.x), float(r.y)), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(float(r.w), float(r.h)), ImGuiCond_Always);
}

// The controls overlay (F1 or ?): every key and mouse action, from the one table.
void help(PlayerApp& app) {
  if (!app.show_help) return;
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::Begin("Controls (F1 or ? to close)", &app.show_help,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
  if (ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg)) {
    for (const Control& c : kControls) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(c.input);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(c.action);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace

namespace {
// What playback reaches: "playing at 9.0 steps/s of 24" when it shows every step slower than
// the speed asks (frames are slower than the steps), else the steps shown per second.
std::string shown_rate_text(const PlayerApp& app) {
  const double shown = app.steps_shown_per_s();
  char text[96];
  if (app.state.every_step && shown < kSlowPlaybackShare * app.state.speed)
    std::snprintf(text, sizeof text, "playing at %.1f steps/s of %.3g", shown, app.state.speed);
  else
    std::snprintf(text, sizeof text, "%.1f shown/s", shown);
  return text;
}
}  // namespace

void timeline_section(PlayerApp& app) {
  using Kind = ScriptAction::Kind;
  const int last = app.steps() - 1;
  // As wide as its wider label, so that the controls beside it do not move when it flips.
  const float play_width =
      ImGui::CalcTextSize("Pause").x + 2 * ImGui::GetStyle().FramePadding.x;
  if (ImGui::Button(app.state.playing ? "Pause" : "Play", ImVec2(play_width, 0)))
    app.command(command_of(app.state.playing ? Kind::pause : Kind::play));
  ImGui::SameLine();
  if (ImGui::Button("|<")) app.command(step_command(0));
  ImGui::SameLine();
  if (ImGui::Button("<")) app.command(step_command(std::max(0, app.state.step - 1)));
  ImGui::SameLine();
  if (ImGui::Button(">")) app.command(step_command(std::min(last, app.state.step + 1)));
  ImGui::SameLine();
  if (ImGui::Button(">|")) app.command(step_command(last));
  ImGui::SameLine();
  if (bool loop = app.state.loop; ImGui::Checkbox("loop", &loop)) app.command(command_of(Kind::loop, loop));
  ImGui::SameLine();
  if (bool skip = !app.state.every_step; ImGui::Checkbox("skip steps", &skip))
    app.command(command_of(Kind::every_step, !skip));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("real time: skip steps to keep the speed when frames are slower than it\n"
                      "(off: every step in order, playing slower if need be)");
  ImGui::SameLine();
  float speed = float(app.state.speed);
  ImGui::SetNextItemWidth(140);
  if (ImGui::SliderFloat("steps/s", &speed, float(kMinSpeed), float(kMaxSpeed), "%.2f",
                         ImGuiSliderFlags_Logarithmic)) {
    ScriptAction a = command_of(Kind::speed);
    a.value = std::clamp(double(speed), kMinSpeed, kMaxSpeed);
    app.command(a);
  }
  if (app.state.playing) {  // the rate the window reaches: distinct steps drawn per second
    ImGui::SameLine();
    ImGui::TextUnformatted(shown_rate_text(app).c_str());
    // The rung and why, on a line of its own that wraps (beside the slider it ran off the panel).
    ImGui::TextWrapped("%s", playback_text(app).c_str());
  }
  int step = app.state.step;
  ImGui::SetNextItemWidth(-1);
  // Dragging the scrubber pauses playback; releasing it resumes if it was playing.
  static bool resume_after_scrub = false;
  const bool was_playing = app.state.playing;
  // The step with its physical time when the file has times ("step 3  t = 0.15").
  const auto& times = app.file->metadata().times;
  char label[96];
  if (times.empty())
    std::snprintf(label, sizeof label, "step %%d");
  else
    std::snprintf(label, sizeof label, "step %%d  t = %s",
                  tsp::format_time(times[std::size_t(app.state.step)], app.file->metadata().time_units)
                      .c_str());
  if (ImGui::SliderInt("##step", &step, 0, last, label))
    app.command(step_command(std::clamp(step, 0, last)));
  if (ImGui::IsItemActivated()) {
    resume_after_scrub = was_playing;
    app.command(command_of(Kind::pause));
  }
  if (ImGui::IsItemDeactivated() && resume_after_scrub) {
    app.command(command_of(Kind::play));
    resume_after_scrub = false;
  }
  // Under the scrubber, each step's readiness: green when its frame reads nothing from the file
  // (bricks in RAM or textures), darker as more of it must still be read.
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const int n = app.steps();
  const float w = (hi.x - lo.x) / float(n);
  for (int t = 0; t < n; ++t) {
    const float r = app.ready[std::size_t(t)];
    if (r < 0) continue;
    const ImU32 col = r >= 1.f ? IM_COL32(70, 200, 90, 255)
                               : IM_COL32(int(60 + 120 * r), int(60 + 100 * r), 60, 255);
    dl->AddRectFilled(ImVec2(lo.x + w * float(t), hi.y + 1),
                      ImVec2(lo.x + w * float(t + 1) - (w > 3 ? 1.f : 0.f),
                             hi.y + 1 + kReadyStripHeight),
                      col);
  }
  ImGui::Dummy(ImVec2(0, kReadyStripHeight));
  if (ImGui::IsItemHovered() || ImGui::IsMouseHoveringRect(ImVec2(lo.x, hi.y),
                                                           ImVec2(hi.x, hi.y + kReadyStripHeight)))
    ImGui::SetTooltip("green: the step's bricks are in memory (no file read to show it)");
}

// Units longer than this go in the widget's tooltip, not its label (the panel is narrow).
constexpr std::size_t kMaxUnitInLabel = 6;

// One widget for a row of the render settings table: a log slider over its panel range (Ctrl +
// click types any value the table accepts), a checkbox or a combo; a change is a `setting`
// command, as a script line makes.
void setting_widget(PlayerApp& app, const tspgl::SettingSpec& spec) {
  const std::string name(spec.name), now = tspgl::get_setting(app.state.settings, spec);
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
      if (ImGui::SliderFloat(label.c_str(), &v, float(spec.ui_lo), float(spec.ui_hi),
                             off_at_zero && v == 0 ? "off" : "%.3g",
                             ImGuiSliderFlags_Logarithmic)) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.9g",
                      std::clamp(double(v), spec.lo, std::min(spec.hi, 1e300)));
        next = buf;
      }
      break;
    }
    case tspgl::SettingKind::toggle: {
      bool on = now == "on";
      if (ImGui::Checkbox(label.c_str(), &on)) next = on ? "on" : "off";
      break;
    }
    case tspgl::SettingKind::choice: {
      int k = 0;
      std::string items;  // ImGui's zero-separated list
      for (std::size_t i = 0; i < spec.choices.size(); ++i) {
        if (spec.choices[i] == now) k = int(i);
        items += std::string(spec.choices[i]) + '\0';
      }
      if (ImGui::Combo(label.c_str(), &k, items.c_str())) next = std::string(spec.choices[std::size_t(k)]);
      break;
    }
  }
  if (ImGui::IsItemHovered())  // the table's help, as render --help says it
    ImGui::SetTooltip("%s%s%s", std::string(spec.help).c_str(), spec.unit.empty() ? "" : "; in ",
                      std::string(spec.unit).c_str());
  if (next.empty()) return;
  ScriptAction a = command_of(ScriptAction::Kind::setting);
  a.text = name;
  a.text2 = next;
  app.command(a);
}

// The widgets of every row of group g but the tolerances (their sliders span the metric's range).
void setting_widgets(PlayerApp& app, tspgl::SettingGroup g) {
  for (const tspgl::SettingSpec& spec : tspgl::settings_table())
    if (spec.group == g && spec.name != "spatial-tol" && spec.name != "temporal-tol")
      setting_widget(app, spec);
}

void settings_section(PlayerApp& app) {
  // Widgets end kLabelWidth short of the window's edge: their labels are never clipped.
  ImGui::PushItemWidth(-kLabelWidth);
  // A file with several fields: which one is shown (each keeps its TF and its caches).
  if (const auto& fields = app.file->fields(); fields.size() > 1) {
    const int current = app.file->field_index();
    if (ImGui::BeginCombo("field", fields[std::size_t(current)].c_str())) {
      for (std::size_t k = 0; k < fields.size(); ++k)
        if (ImGui::Selectable(fields[k].c_str(), int(k) == current)) {
          ScriptAction a = command_of(ScriptAction::Kind::field);
          a.text = fields[k];
          app.command(a);
        }
      ImGui::EndCombo();
    }
  }
  ImGui::Checkbox("outline, axes, step", &app.state.annotations);
  int m = int(app.state.metric);
  if (ImGui::Combo("metric", &m, kMetricNames, IM_ARRAYSIZE(kMetricNames)))
    app.command([m] {
      ScriptAction a = command_of(ScriptAction::Kind::metric);
      a.text = tsp::to_string(tsp::Metric(m));
      return a;
    }());
  if (app.state.metric == tsp::Metric::reference)
    ImGui::TextWrapped(
        "reference: every voxel is read; computed in full on each TF change "
        "(the window waits)");
  else
    ImGui::TextWrapped("live: only the nodes a frame visits are recomputed after a TF edit");

  float s = float(app.state.settings.tol.spatial), t = float(app.state.settings.tol.temporal);
  bool changed =
      ImGui::SliderFloat("spatial tol", &s, 0.f, app.tol_max, "%.4g", ImGuiSliderFlags_Logarithmic);
  bool done = ImGui::IsItemDeactivatedAfterEdit();
  changed |= ImGui::SliderFloat("temporal tol", &t, 0.f, app.tol_max, "%.4g",
                                ImGuiSliderFlags_Logarithmic);
  done |= ImGui::IsItemDeactivatedAfterEdit();
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s; 0 = exact", kToleranceUnits[int(app.state.metric)]);
  ImGui::PopStyleColor();
  // Frames follow the slider at once; unreachable textures are dropped when it is released.
  if (changed) app.state.settings.tol = {double(s), double(t)};
  if (done) app.set_tolerances(app.state.settings.tol);

  setting_widgets(app, tspgl::SettingGroup::quality);
  setting_widgets(app, tspgl::SettingGroup::compositing);
  if (ImGui::TreeNode("diagnostics")) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the paper's rules, our optimisations off");
    setting_widgets(app, tspgl::SettingGroup::diagnostics);
    ImGui::TreePop();
  }
  // While playing, the quality target picks the rung of the tuned ladder (the knobs above made
  // cheaper: spacing, render scale, LOD level) that fits the speed within the target.
  float quality = app.state.quality;
  ImGui::SliderFloat("playing quality (mean dE)", &quality, 0.f, 10.f, quality > 0 ? "%.2f" : "off");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("while playing: mean dE against the full-quality picture (paused: always "
                      "full quality); off: the LOD cut holds the frame rate");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    ScriptAction a = command_of(ScriptAction::Kind::quality);
    a.value = quality;
    app.command(a);
  }
  if (const tspgl::PlaybackTuner* t = app.tuning()) {  // runs a slice of each frame
    const int total = std::max(1, t->pictures_total());
    char text[64];
    std::snprintf(text, sizeof text, "tuning playback %d / %d", t->pictures_done(), total);
    ImGui::ProgressBar(float(t->pictures_done()) / float(total), ImVec2(-1, 0), text);
  }
  if (app.state.quality > 0) {
    ImGui::TextUnformatted("while playing, keep:");
    ImGui::SameLine();
    if (ImGui::RadioButton("quality", app.state.keep_quality))
      app.command(command_of(ScriptAction::Kind::playback, true));
    ImGui::SameLine();
    if (ImGui::RadioButton("rate", !app.state.keep_quality))
      app.command(command_of(ScriptAction::Kind::playback, false));
  }
  // Level of detail: the cut holds the frame rate while anything changes, full quality when idle.
  bool lod = app.state.lod_on;
  if (ImGui::Checkbox("level of detail", &lod))
    app.command(command_of(ScriptAction::Kind::lod, lod));
  ImGui::SameLine();
  if (bool cut = app.state.show_cut; ImGui::Checkbox("show cut (L)", &cut))
    app.command(command_of(ScriptAction::Kind::show_cut, cut));
  if (float fps = app.state.target_fps; ImGui::SliderFloat("target fps", &fps, 5.f, 120.f, "%.0f")) {
    ScriptAction a = command_of(ScriptAction::Kind::target_fps);
    a.value = std::clamp(double(fps), 1.0, kMaxTargetFps);
    app.command(a);
  }
  ImGui::Checkbox("splats when the coarsest cut is too slow", &app.state.splat_fallback);
  // How the cut is chosen: by error against the target, or by LaMar's selection filters.
  {
    static const char* const kFilters[] = {"error (target fps)", "distance from the eye",
                                           "field of view"};
    int kind = int(app.state.lod_filter.kind);
    float k = float(app.state.lod_filter.scale);
    ImGui::SetNextItemWidth(170);
    const bool picked = ImGui::Combo("cut by", &kind, kFilters, 3);
    bool scaled = false;
    if (kind != 0) {
      ImGui::SameLine();
      ImGui::SetNextItemWidth(90);
      scaled = ImGui::SliderFloat("K", &k, 0.25f, 8.f, "%.2f", ImGuiSliderFlags_Logarithmic);
    }
    if (picked || scaled) {
      ScriptAction a = command_of(ScriptAction::Kind::lod_filter);
      const char* const names[] = {"error", "distance", "fov"};
      char text[64];
      std::snprintf(text, sizeof text, "%s:%g", names[kind], double(k));
      a.text = kind == 0 ? "error" : text;
      app.command(a);
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("LaMar's filters: a tile is drawn whole when the eye is more than K\n"
                        "diagonals away (distance) or when it subtends less than half the\n"
                        "field of view over K (fov; outside the view: not refined)");
  }

  if (ImGui::TreeNode("caches and uploads")) {
    bool cache = app.state.cache_on;
    if (ImGui::Checkbox("texture cache", &cache))
      app.command(command_of(ScriptAction::Kind::cache, cache));
    ImGui::SameLine();
    if (bool on = app.state.prefetch_on; ImGui::Checkbox("prefetch", &on))
      app.command(command_of(ScriptAction::Kind::prefetch, on));
    setting_widgets(app, tspgl::SettingGroup::memory);
    static double budget = -1;
    if (budget < 0) budget = app.state.texture_budget_mb;
    ImGui::SetNextItemWidth(120);
    ImGui::InputDouble("budget MiB", &budget, 16, 128, "%.0f");
    if (ImGui::IsItemDeactivatedAfterEdit()) app.set_cache(app.state.cache_on, budget);
    ImGui::TreePop();
  }

  // Physical proportions from the file's voxel spacing, stretched per axis (e.g. height).
  axis_scale_field(app);
  int proj = app.state.camera.projection == tsp::Projection::perspective;
  ImGui::RadioButton("orthographic", &proj, 0);
  ImGui::SameLine();
  ImGui::RadioButton("perspective", &proj, 1);
  app.state.camera.projection = proj ? tsp::Projection::perspective : tsp::Projection::orthographic;
  if (ImGui::Button("save PNG (S)")) app.request_save();
  ImGui::SameLine();
  if (ImGui::Button("reset view (R)")) {
    const int w = app.state.camera.width, h = app.state.camera.height;
    app.state.camera = app.initial_camera;
    app.state.camera.width = w;
    app.state.camera.height = h;
  }
  if (!app.status.empty()) ImGui::TextWrapped("%s", app.status.c_str());
  ImGui::PopItemWidth();
}

void stats_section(PlayerApp& app) {
  // A temporal tolerance that merged steps says which steps' bricks the picture shows.
  const tspgl::FrameReport& lf = app.last;
  if (app.state.settings.tol.temporal > 0 && lf.spans_hi > lf.spans_lo) {  // (at 0 only unchanging data merge)
    char note[128];
    if (lf.shows_mean)
      std::snprintf(note, sizeof note, "temporal tolerance: showing means over steps %d-%d",
                    lf.spans_lo, lf.spans_hi);
    else if (lf.shown_lo == lf.shown_hi)
      std::snprintf(note, sizeof note, "temporal tolerance: showing step %d for steps %d-%d",
                    lf.shown_lo, lf.spans_lo, lf.spans_hi);
    else
      std::snprintf(note, sizeof note, "temporal tolerance: showing steps %d-%d for steps %d-%d",
                    lf.shown_lo, lf.shown_hi, lf.spans_lo, lf.spans_hi);
    ImGui::TextColored(ImVec4(1.f, 0.75f, 0.3f, 1.f), "%s", note);
  }
  std::vector<float> ms;
  double sum = 0;
  for (const FrameSample& f : app.history) {
    ms.push_back(float(f.ms));
    sum += f.ms;
  }
  const double mean = ms.empty() ? 0 : sum / double(ms.size());
  ImGui::Text("frame %.1f ms (mean %.1f), %.1f fps", ms.empty() ? 0.0 : double(ms.back()), mean,
              mean > 0 ? 1000.0 / mean : 0.0);
  if (!ms.empty())
    ImGui::PlotLines("##ms", ms.data(), int(ms.size()), 0, "frame ms, last 5 s", 0.f,
                     *std::max_element(ms.begin(), ms.end()) * 1.1f,
                     ImVec2(ImGui::GetContentRegionAvail().x, kHudPlotHeight));
  const tspgl::FrameReport& r = app.last;
  // What the last frame drew and its time (player_refine.cpp): never "holding the target"
  // for a frame that missed it.
  ImGui::TextWrapped("%s", app.lod_line().c_str());
  ImGui::Text("render %.1f ms: traversal %.1f, slicing %.1f,\n  upload %.1f, draw %.1f", r.ms,
              r.traversal_ms, r.slicing_ms, r.upload_ms, r.draw_ms);
  const double pixels = std::max(1.0, double(app.layout.view.w) * app.layout.view.h);
  // The picture's fragments: those of the frame that last drew it (a frame that reused the whole
  // image draws none, and said 0 for a picture that plainly shows).
  const double fragments = double(app.picture_fragments());
  ImGui::Text("fragments %.2f M (%.2f per pixel)%s, %s, spacing %.2g", fragments / 1e6,
              fragments / pixels, r.redrawn_percent == 0 ? ", image reused" : "",
              tspgl::to_string(app.state.settings.compositing), app.state.settings.spacing);
  for (int c = 0; c < tsp::kDrawClassCount; ++c)
    ImGui::Text("%-15s %5.1f %%", kClassNames[c], r.class_percent[std::size_t(c)]);
  ImGui::Text("textures %lld resident, %.1f MiB", static_cast<long long>(r.textures_resident),
              double(r.texture_bytes) / kBytesPerMiB);
  ImGui::Text("uploaded this frame %.2f MiB", double(r.bytes_uploaded) / kBytesPerMiB);
  if (!r.complete())
    ImGui::TextColored(ImVec4(1, 0.8f, 0.2f, 1),
                       "%lld textures wait for later frames (flat meanwhile)",
                       static_cast<long long>(r.deferred_textures));
  ImGui::Text("metric recompute %.2f ms (%lld nodes)", app.metric_ms,
              static_cast<long long>(app.metric_evaluations));
  const tsp::BrickCacheStats b = app.renderer->brick_cache().stats();
  ImGui::Text("bricks in RAM %lld (%.1f MiB)\n  %lld hits, %lld misses, %lld prefetched",
              static_cast<long long>(b.resident_count), double(b.resident_bytes) / kBytesPerMiB,
              static_cast<long long>(b.hits), static_cast<long long>(b.misses),
              static_cast<long long>(b.prefetched));
}

void PlayerApp::draw_ui() {
  if (state.panels) {
    if (layout.docked) {
      // One side panel of collapsible sections beside the volume, the timeline under it.
      place(layout.side);
      ImGui::Begin("##side", nullptr, kDockedFlags);
      if (ImGui::CollapsingHeader("Settings", ImGuiTreeNodeFlags_DefaultOpen))
        settings_section(*this);
      if (ImGui::CollapsingHeader("Transfer function", ImGuiTreeNodeFlags_DefaultOpen))
        tf_section(*this);
      if (ImGui::CollapsingHeader("Probes", state.probes.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
        probes_section(*this);
      if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen))
        stats_section(*this);
      ImGui::End();
      place(layout.timeline);
      ImGui::Begin("##timeline", nullptr, kDockedFlags);
      timeline_section(*this);
      ImGui::End();
    } else {
      // A small window: the sections float over the volume, collapsed to their titles at first
      // (a click opens one) so that the volume stays in sight.
      const float w = float(ctx->width()), h = float(ctx->height());
      const float top = ImGui::GetFrameHeight() + 4;
      ImGui::SetNextWindowPos(ImVec2(10, h - 110), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowSize(ImVec2(w - 20, 100), ImGuiCond_FirstUseEver);
      ImGui::Begin("Timeline");
      timeline_section(*this);
      ImGui::End();
      ImGui::SetNextWindowPos(ImVec2(10, top), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowSize(ImVec2(340, 260), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
      ImGui::Begin("Settings");
      settings_section(*this);
      ImGui::End();
      ImGui::SetNextWindowPos(ImVec2(std::max(10.f, w - 390), top), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowSize(ImVec2(380, 330), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
      ImGui::Begin("Statistics");
      stats_section(*this);
      ImGui::End();
      ImGui::SetNextWindowPos(ImVec2(10, top + 2 * ImGui::GetFrameHeight()), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowSize(ImVec2(340, 330), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
      ImGui::Begin("Transfer function");
      tf_section(*this);
      ImGui::End();
      ImGui::SetNextWindowPos(ImVec2(10, top + 3 * ImGui::GetFrameHeight()), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowSize(ImVec2(340, 240), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
      ImGui::Begin("Probes");
      probes_section(*this);
      ImGui::End();
    }
  }
  help(*this);
  // Last, after every window that may appear this frame: Dear ImGui 1.86 aborts ("ImGui::Begin:
  // Assertion `blocking_modal != NULL'") when a window appears after a modal begun for the first
  // time in the same frame — File > Open's progress dialog opened in the first frames, before
  // the panels had appeared (issue 28).
  if (state.panels) menu_and_dialogs(*this);
}

}  // namespace tspplayer
