// The player's Dear ImGui panels: timeline, view and metric settings, heads-up statistics and
// the transfer-function editor. Drawn after the volume each frame (docs/player.md).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "player/controls.h"
#include "player/player_app.h"
#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

namespace {

constexpr float kMaxSpeed = 60.f;  // steps per second
constexpr float kMinSpeed = 0.25f;
constexpr float kHistogramHeight = 80.f;
constexpr float kHudPlotHeight = 60.f;
constexpr float kHandleRadius = 5.f;
constexpr float kLabelWidth = 130.f;  // room for a settings label, pixels  // TF control point handles, pixels
constexpr double kBytesPerMiB = 1 << 20;
constexpr const char* kMetricNames[] = {"scalar", "reference", "approximate", "perceptual"};
// In tspgl::Compositing order.
constexpr const char* kCompositingNames[] = {"slices", "boxes", "rays"};
constexpr const char* kClassNames[] = {"not rendered", "untextured", "reused texture",
                                       "new texture"};

void timeline(PlayerApp& app) {
  ImGui::SetNextWindowPos(ImVec2(10, float(app.ctx->height()) - 110), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(float(app.ctx->width()) - 20, 100), ImGuiCond_FirstUseEver);
  ImGui::Begin("Timeline");
  if (ImGui::Button(app.playing ? "Pause" : "Play")) app.playing = !app.playing;
  ImGui::SameLine();
  if (ImGui::Button("|<")) app.go_to(0);
  ImGui::SameLine();
  if (ImGui::Button("<")) app.go_to(app.step - 1);
  ImGui::SameLine();
  if (ImGui::Button(">")) app.go_to(app.step + 1);
  ImGui::SameLine();
  if (ImGui::Button(">|")) app.go_to(app.steps() - 1);
  ImGui::SameLine();
  ImGui::Checkbox("loop", &app.loop);
  ImGui::SameLine();
  float speed = float(app.speed);
  ImGui::SetNextItemWidth(160);
  if (ImGui::SliderFloat("steps/s", &speed, kMinSpeed, kMaxSpeed, "%.2f",
                         ImGuiSliderFlags_Logarithmic))
    app.speed = std::clamp(double(speed), double(kMinSpeed), double(kMaxSpeed));
  int step = app.step;
  ImGui::SetNextItemWidth(-1);
  // Dragging the scrubber pauses playback; releasing it resumes if it was playing.
  static bool resume_after_scrub = false;
  const bool was_playing = app.playing;
  // The step with its physical time when the file has times ("step 3  t = 0.15").
  const auto& times = app.file->metadata().times;
  char label[64];
  if (times.empty())
    std::snprintf(label, sizeof label, "step %%d");
  else
    std::snprintf(label, sizeof label, "step %%d  t = %g", times[std::size_t(app.step)]);
  if (ImGui::SliderInt("##step", &step, 0, app.steps() - 1, label)) app.go_to(step);
  if (ImGui::IsItemActivated()) {
    resume_after_scrub = was_playing;
    app.playing = false;
  }
  if (ImGui::IsItemDeactivated() && resume_after_scrub) {
    app.playing = true;
    resume_after_scrub = false;
  }
  ImGui::End();
}

void settings(PlayerApp& app) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 260), ImGuiCond_FirstUseEver);
  ImGui::Begin("Settings");
  // Widgets end kLabelWidth short of the window's edge: their labels are never clipped.
  ImGui::PushItemWidth(-kLabelWidth);
  ImGui::Checkbox("outline, axes, step", &app.annotations);
  int m = int(app.metric);
  if (ImGui::Combo("metric", &m, kMetricNames, IM_ARRAYSIZE(kMetricNames)))
    app.set_metric(tsp::Metric(m));
  if (app.metric == tsp::Metric::reference)
    ImGui::TextWrapped(
        "reference: every voxel is read; computed in full on each TF change "
        "(the window waits)");
  else
    ImGui::TextWrapped("live: only the nodes a frame visits are recomputed after a TF edit");

  float s = float(app.tol.spatial), t = float(app.tol.temporal);
  bool changed =
      ImGui::SliderFloat("spatial tol", &s, 0.f, app.tol_max, "%.4g", ImGuiSliderFlags_Logarithmic);
  bool done = ImGui::IsItemDeactivatedAfterEdit();
  changed |= ImGui::SliderFloat("temporal tol", &t, 0.f, app.tol_max, "%.4g",
                                ImGuiSliderFlags_Logarithmic);
  done |= ImGui::IsItemDeactivatedAfterEdit();
  // Frames follow the slider at once; unreachable textures are dropped when it is released.
  if (changed) app.tol = {double(s), double(t)};
  if (done) app.set_tolerances(app.tol);

  int comp = int(app.compositing);
  if (ImGui::Combo("compositing", &comp, kCompositingNames, IM_ARRAYSIZE(kCompositingNames)))
    app.compositing = tspgl::Compositing(comp);
  float sp = float(app.spacing);
  if (ImGui::SliderFloat("spacing (voxels)", &sp, 0.25f, 8.f, "%.2f", ImGuiSliderFlags_Logarithmic))
    app.spacing = std::clamp(double(sp), tspgl::kMinSliceSpacing, tspgl::kMaxSliceSpacing);
  ImGui::Checkbox("pre-integrated TF", &app.preintegrated);
  // The quality target sets all of the knobs above from a calibration (made once, cached).
  ImGui::SliderFloat("quality (dE)", &app.quality, 0.f, 10.f, app.quality > 0 ? "%.2f" : "off");
  if (ImGui::IsItemDeactivatedAfterEdit() && app.quality > 0) {
    app.status = "calibrating (once per tree, TF, metric and view) ...";
    app.apply_quality(app.quality);
    app.status.clear();
  }
  if (!app.quality_note.empty()) ImGui::TextWrapped("quality: %s", app.quality_note.c_str());
  // Level of detail: the cut holds the frame rate while anything changes, full quality when idle.
  bool lod = app.lod_on;
  if (ImGui::Checkbox("level of detail", &lod)) app.set_lod(lod);
  ImGui::SameLine();
  ImGui::Checkbox("show cut (L)", &app.show_cut);
  ImGui::SliderFloat("target fps", &app.target_fps, 5.f, 120.f, "%.0f");

  bool cache = app.cache_on;
  if (ImGui::Checkbox("texture cache", &cache)) app.set_cache(cache, app.texture_budget_mb);
  ImGui::SameLine();
  ImGui::Checkbox("prefetch", &app.prefetch_on);
  float upload = float(app.upload_budget_mb);
  if (ImGui::SliderFloat("upload MiB/frame", &upload, 0.f, 256.f, upload > 0 ? "%.1f" : "no limit",
                         ImGuiSliderFlags_Logarithmic))
    app.upload_budget_mb = std::max(0.0, double(upload));
  static double budget = -1;
  if (budget < 0) budget = app.texture_budget_mb;
  ImGui::SetNextItemWidth(120);
  ImGui::InputDouble("budget MiB", &budget, 16, 128, "%.0f");
  if (ImGui::IsItemDeactivatedAfterEdit()) app.set_cache(app.cache_on, budget);

  int proj = app.camera.projection == tsp::Projection::perspective;
  ImGui::RadioButton("orthographic", &proj, 0);
  ImGui::SameLine();
  ImGui::RadioButton("perspective", &proj, 1);
  app.camera.projection = proj ? tsp::Projection::perspective : tsp::Projection::orthographic;
  if (ImGui::Button("save PNG (S)")) app.request_save();
  ImGui::SameLine();
  if (ImGui::Button("reset view")) {
    const int w = app.camera.width, h = app.camera.height;
    app.camera = tsp::CameraParams{};
    app.camera.width = w;
    app.camera.height = h;
  }
  if (!app.status.empty()) ImGui::TextWrapped("%s", app.status.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
}

void hud(PlayerApp& app) {
  ImGui::SetNextWindowPos(ImVec2(float(app.ctx->width()) - 390, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(380, 330), ImGuiCond_FirstUseEver);
  ImGui::Begin("Statistics");
  // A temporal tolerance that merged steps says which step's bricks the picture shows.
  const tspgl::FrameReport& lf = app.last;
  if (app.tol.temporal > 0 && lf.spans_hi > lf.spans_lo) {  // (at 0 only unchanging data merge)
    char note[128];
    if (lf.shown_lo == lf.shown_hi)
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
  if (app.lod_on) {
    std::string levels;
    for (std::size_t k = 0; k < app.lod_stats.nodes_per_level.size(); ++k)
      levels += (k ? " " : "") + std::to_string(app.lod_stats.nodes_per_level[k]);
    ImGui::Text("LOD %s: cut %d nodes [by level %s], scale %.2f",
                app.refining ? "refining to full" : "holding the target", app.lod_stats.cut_size,
                levels.c_str(), app.lod_stats.render_scale);
  }
  ImGui::Text("render %.1f ms: traversal %.1f, slicing %.1f,\n  upload %.1f, draw %.1f", r.ms,
              r.traversal_ms, r.slicing_ms, r.upload_ms, r.draw_ms);
  ImGui::Text("fragments %.2f M (%.2f per pixel), %s, spacing %.2g", double(r.fragments) / 1e6,
              double(r.fragments) / std::max(1.0, double(app.ctx->width()) * app.ctx->height()),
              tspgl::to_string(app.compositing), app.spacing);
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
  ImGui::End();
}

void tf_editor(PlayerApp& app) {
  ImGui::SetNextWindowPos(ImVec2(10, 280), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 330), ImGuiCond_FirstUseEver);
  ImGui::Begin("Transfer function");
  // Histogram (log counts) with the opacity curve drawn over it.
  const auto& hist = app.file->metadata().histogram;
  std::vector<float> logh;
  for (std::uint64_t c : hist) logh.push_back(std::log1p(float(c)));
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const tsp::ValueRange d = app.tf.domain();
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
  }
  const int n = app.tf.size();
  for (int j = 1; j < n; ++j) {
    const tsp::Rgba a = app.tf.entry(j - 1), b = app.tf.entry(j);
    // Entries at their values, so the curve and the handles share the TF domain's scale.
    const float x0 = origin.x + width * float((app.tf.entry_value(j - 1) - d.lo) / (d.hi - d.lo));
    const float x1 = origin.x + width * float((app.tf.entry_value(j) - d.lo) / (d.hi - d.lo));
    dl->AddLine(ImVec2(x0, origin.y + kHistogramHeight * (1 - a.a)),
                ImVec2(x1, origin.y + kHistogramHeight * (1 - b.a)),
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
    return ImVec2(origin.x + width * float((p.x - d.lo) / span),
                  origin.y + kHistogramHeight * (1 - p.c.a));
  };
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const double mouse_x = std::clamp(d.lo + double(mouse.x - origin.x) / width * span, d.lo, d.hi);
  const float mouse_a = std::clamp(1.f - (mouse.y - origin.y) / kHistogramHeight, 0.f, 1.f);
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
  ImGui::TextDisabled("drag a point; double-click adds, right-click removes");
  for (std::size_t i = 0; i < app.tf_points.size(); ++i) {
    tsp::TfPoint& p = app.tf_points[i];
    ImGui::PushID(int(i));
    float x = float(p.x);
    ImGui::SetNextItemWidth(110);
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
    ImGui::SetNextItemWidth(90);
    if (ImGui::SliderFloat("##a", &c[3], 0.f, 1.f, "a %.3f")) {
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

  static int preset = 0;
  const std::vector<std::string> names = tsp::preset_names();
  std::vector<const char*> cnames;
  for (const auto& s : names) cnames.push_back(s.c_str());
  ImGui::SetNextItemWidth(120);
  ImGui::Combo("##preset", &preset, cnames.data(), int(cnames.size()));
  ImGui::SameLine();
  if (ImGui::Button("apply preset"))
    app.set_tf(tsp::preset_transfer_function(names[std::size_t(preset)], d, app.tf.size()), true);
  ImGui::SameLine();
  if (ImGui::Button("fit to data")) {  // the map as it is, stretched over the data's range
    app.set_tf(tsp::rescaled(app.tf, d), true);
    app.status = "transfer function stretched over the data range";
  }

  static char path[512] = "";
  if (path[0] == 0) std::snprintf(path, sizeof path, "%s", app.tf_path.c_str());
  ImGui::SetNextItemWidth(-1);
  ImGui::InputText("##path", path, sizeof path);
  app.tf_path = path;
  try {
    if (ImGui::Button("load")) {
      app.set_tf(tsp::transfer_function_from_arg(app.tf_path, d, app.tf.size()), true);
      const std::string w = tsp::tf_range_warning(app.tf, app.file->metadata().data_range);
      app.status = w.empty() ? "loaded " + app.tf_path : "loaded " + app.tf_path + "; " + w;
    }
    ImGui::SameLine();
    if (ImGui::Button("save")) {
      tsp::save_transfer_function(app.tf, app.tf_path);
      app.status = "saved " + app.tf_path;
    }
  } catch (const tsp::Error& e) {
    app.status = e.what();  // shown in the settings panel; the player keeps running
  }
  ImGui::End();
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

void PlayerApp::draw_ui() {
  timeline(*this);
  settings(*this);
  hud(*this);
  tf_editor(*this);
  help(*this);
}

}  // namespace tspplayer
