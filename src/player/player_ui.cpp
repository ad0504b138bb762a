// The player's Dear ImGui panels: the layout (docked beside the volume, floating over it in a
// small window, or hidden), the settings, statistics and timeline sections, the controls
// overlay. Drawn after the volume each frame (docs/player.md).
#include <imgui.h>
#include <imgui_internal.h>  // FindRenderedTextEnd: a label's shown part

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>

#include "player/axis_scale_field.h"
#include "player/controls.h"
#include "player/player_app.h"
#include "player/player_ui.h"
#include "player/slider_text.h"
#include "player/ui_items.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {

// What playback draws and which of rate and quality gives, for the transport line.
std::string playback_text(const PlayerApp& app) {
  if (app.state().quality <= 0) return "(LOD cut holds the rate)";
  if (app.tuning() && app.tuned_rungs().empty()) return "(spacing x2, scale 0.5 while tuning)";
  if (!app.playing_rung()) return "";
  const tspgl::TunedRung& t = app.tuned_rungs()[std::size_t(app.rung_choice().index)];
  char text[160];
  if (!app.rung_choice().within_quality)
    std::snprintf(text, sizeof text, "%s, dE %.2f: keeping rate, quality gives", t.rung.name, t.mean_de);
  else if (!app.rung_choice().fits_rate)  // late, or skipped with "skip steps" ticked
    std::snprintf(text, sizeof text, "%s, dE %.2f: keeping quality, %s", t.rung.name, t.mean_de,
                  app.state().every_step ? "steps late" : "skipping steps");
  else
    std::snprintf(text, sizeof text, "%s, dE %.2f", t.rung.name, t.mean_de);
  return text;
}

constexpr float kHudPlotHeight = 60.f;
// Lines of the side panel's status area; widest tooltip, pixels.
constexpr int kStatusLines = 5;
constexpr float kTooltipWidth = 420.f;
constexpr float kReadyStripHeight = 5.f;  // the timeline's readiness marks, pixels
constexpr double kBytesPerMiB = 1 << 20;
// In tspgl::Compositing order.
constexpr const char* kClassNames[] = {"not rendered", "untextured", "reused texture",
                                       "new texture", "clipped"};
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
  if (!app.help_shown()) return;
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(1.f);  // (over the picture: the text on an opaque background)
  bool open = true;  // (its close box: closed from the next frame on)
  ImGui::Begin("Controls (F1 or ? to close)", &open,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
  if (!open) app.push(cmd::ShowHelp{false});
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
  if (app.state().every_step && app.rate_slow())  // (with hysteresis: one steady answer)
    std::snprintf(text, sizeof text, "playing at %s steps/s of %.3g", rate_text(shown).c_str(),
                  app.state().speed);
  else
    std::snprintf(text, sizeof text, "%s shown/s", rate_text(shown).c_str());
  return text;
}
// Hides the value text Dear ImGui centres on the next slider's frame (unless it is being typed
// into: Ctrl+click), for value_beside_grab to draw it where the grab cannot cover it.
bool hide_slider_text(const char* id) {
  const bool typing = ImGui::TempInputIsActive(ImGui::GetID(id));
  if (!typing) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0, 0, 0, 0));
  return !typing;
}

// The value text on the last slider's frame [x0, x1] beside its grab (slider_text.h).
void value_beside_grab(float x0, float x1, GrabSpan grab, const char* text) {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  const ImVec2 size = ImGui::CalcTextSize(text);
  const float y = lo.y + (hi.y - lo.y - size.y) * 0.5f;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  if (!room_beside_grab(x0, x1, grab, size.x)) {  // (one value: over the grab, centred)
    dl->AddText(ImVec2(0.5f * (x0 + x1 - size.x), y), ImGui::GetColorU32(ImGuiCol_Text), text);
    return;
  }
  const float x = text_beside_grab(x0, x1, grab, size.x);
  const bool left = x < grab.lo;  // (clipped at the grab: never under it)
  dl->PushClipRect(ImVec2(left ? x0 : grab.hi, lo.y), ImVec2(left ? grab.lo : x1, hi.y), true);
  dl->AddText(ImVec2(x, y), ImGui::GetColorU32(ImGuiCol_Text), text);
  dl->PopClipRect();
}

// Under the scrubber (the last item), each step's readiness: green when its frame reads nothing
// from the file (bricks in RAM or textures), darker as more of it must still be read.
void ready_strip(const PlayerApp& app) {
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
    tooltip("green: the step's bricks are in memory (no file read to show it)");
}

}  // namespace

void timeline_section(PlayerApp& app) {
  const int last = app.steps() - 1;
  // As wide as its wider label, so that the controls beside it do not move when it flips.
  const float play_width =
      std::max(ImGui::CalcTextSize("Pause").x, ImGui::CalcTextSize("Play").x) +
      2 * ImGui::GetStyle().FramePadding.x;
  const char* play = app.state().playing ? "Pause" : "Play";
  if (ImGui::Button(play, ImVec2(play_width, 0)))
    app.push(app.state().playing ? Command(cmd::Pause{}) : Command(cmd::Play{}));
  note_item(play, true);
  for (const char* b : {"|<", "<", ">", ">|"}) {
    ImGui::SameLine();
    if (ImGui::Button(b)) {
      const int to = b[1] == '<' ? 0 : b[1] == '|' ? last
                     : b[0] == '<' ? std::max(0, app.state().step - 1)
                                   : std::min(last, app.state().step + 1);
      app.push(cmd::GoToStep{to});
    }
    note_item(b, true);
  }
  ImGui::SameLine();
  if (bool loop = app.state().loop; ImGui::Checkbox("loop", &loop)) app.push(cmd::SetLoop{loop});
  note_item("loop");
  ImGui::SameLine();
  if (bool skip = !app.state().every_step; ImGui::Checkbox("skip steps", &skip))
    app.push(cmd::EveryStep{!skip});
  note_item("skip steps");
  if (ImGui::IsItemHovered())
    tooltip("real time: skip steps to keep the speed when frames are slower than it (off: every "
            "step in order, playing slower if need be)");
  ImGui::SameLine();
  float speed = float(app.state().speed);
  // 140 pixels, less in a narrow window (the slider and its label stay inside the timeline).
  const float room = ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("steps/s").x -
                     ImGui::GetStyle().ItemInnerSpacing.x;
  const float speed_w = std::clamp(room, 60.f, 140.f);
  ImGui::SetNextItemWidth(speed_w);
  // (Its value beside the grab, where the grab cannot cover it.)
  const bool speed_hidden = hide_slider_text("steps/s");
  const bool speed_moved = ImGui::SliderFloat("steps/s", &speed, float(kMinSpeed),
                                              float(kMaxSpeed), "%.2f", ImGuiSliderFlags_Logarithmic);
  if (speed_hidden) {
    ImGui::PopStyleColor();
    const float x0 = ImGui::GetItemRectMin().x;
    char value[32];
    std::snprintf(value, sizeof value, "%.2f", speed);
    value_beside_grab(x0, x0 + speed_w,
                      slider_grab(x0, x0 + speed_w,
                                  std::log(double(speed) / kMinSpeed) / std::log(kMaxSpeed / kMinSpeed),
                                  ImGui::GetStyle().GrabMinSize),
                      value);
    // (The label, hidden with the value: drawn where ImGui puts it.)
    const ImGuiStyle& st = ImGui::GetStyle();
    ImGui::GetWindowDrawList()->AddText(
        ImVec2(x0 + speed_w + st.ItemInnerSpacing.x, ImGui::GetItemRectMin().y + st.FramePadding.y),
        ImGui::GetColorU32(ImGuiCol_Text), "steps/s");
  }
  if (speed_moved) app.push(cmd::SetSpeed{std::clamp(double(speed), kMinSpeed, kMaxSpeed)});
  note_item("steps/s");
  // The rate the window reaches, at the row's end (nothing after it), once one was measured.
  if (app.rate_measured()) {
    ImGui::SameLine();
    ImGui::TextUnformatted(shown_rate_text(app).c_str());
    note_item(shown_rate_text(app).c_str());
    // (The rung and why: in the side panel's status area, which never moves the controls.)
  }
  int step = app.state().step;
  ImGui::SetNextItemWidth(-1);
  // Dragging the scrubber pauses playback; releasing it resumes if it was playing.
  static bool resume_after_scrub = false;
  const bool was_playing = app.state().playing;
  // The step with its physical time when the file has times ("step 3  t = 0.15").
  const auto& times = app.viewer().file().metadata().times;
  char label[96];
  if (times.empty())
    std::snprintf(label, sizeof label, "step %%d");
  else
    std::snprintf(label, sizeof label, "step %%d  t = %s",
                  tsp::format_time(times[std::size_t(app.state().step)], app.viewer().file().metadata().time_units)
                      .c_str());
  // (Its text beside the grab, where the grab cannot cover it: with few steps the grab is wide.)
  const bool step_hidden = hide_slider_text("##step");
  const bool scrubbed = ImGui::SliderInt("##step", &step, 0, last, label);
  if (step_hidden) {
    ImGui::PopStyleColor();
    const float x0 = ImGui::GetItemRectMin().x, x1 = ImGui::GetItemRectMax().x;
    char text[128];
    std::snprintf(text, sizeof text, label, step);
    value_beside_grab(
        x0, x1,
        slider_grab(x0, x1, last > 0 ? double(step) / last : 0.0,
                    int_slider_grab_width(x0, x1, 0, last, ImGui::GetStyle().GrabMinSize)),
        text);
  }
  if (scrubbed) app.push(cmd::GoToStep{std::clamp(step, 0, last)});
  if (ImGui::IsItemActivated()) {
    resume_after_scrub = was_playing;
    app.push(cmd::Pause{});
  }
  if (ImGui::IsItemDeactivated() && resume_after_scrub) {
    app.push(cmd::Play{});
    resume_after_scrub = false;
  }
  ready_strip(app);
}

std::string fit_label(const char* label, float min_item_w) {
  const char* end = ImGui::FindRenderedTextEnd(label);
  const float text_w = ImGui::CalcTextSize(label, end).x;
  const float avail = ImGui::GetContentRegionAvail().x;
  const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
  if (end == label || avail - text_w - spacing >= min_item_w) {
    ImGui::SetNextItemWidth(end == label ? avail : avail - text_w - spacing);
    return label;
  }
  // The label on its own line, the item under it as wide as the row.
  ImGui::TextUnformatted(label, end);
  note_item(std::string(label, end).c_str());
  ImGui::SetNextItemWidth(avail);
  return "##" + std::string(label);
}

std::string fit_lines(const std::string& text, float width, float height) {
  auto fits = [&](const std::string& t) {
    return ImGui::CalcTextSize(t.c_str(), nullptr, false, width).y <= height;
  };
  if (text.empty() || fits(text)) return text;
  std::size_t lo = 0, hi = text.size();  // the longest prefix that fits with "..." after it
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (fits(text.substr(0, mid) + "...")) lo = mid;
    else hi = mid - 1;
  }
  return text.substr(0, lo) + "...";
}

void tooltip(const char* text) {
  ImGui::BeginTooltip();
  // Wrapped well inside the window (Dear ImGui keeps the tooltip itself on screen).
  const float w = std::min(kTooltipWidth, ImGui::GetIO().DisplaySize.x * 0.45f);
  ImGui::PushTextWrapPos(ImGui::GetCursorPos().x + w);
  ImGui::TextUnformatted(text);
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

void view_section(PlayerApp& app) {
  if (bool on = app.state().annotations; ImGui::Checkbox("outline, axes, step, legend", &on))
    app.push(cmd::ShowAnnotations{on});
  note_item("outline, axes, step, legend");
  int proj = app.state().camera.projection == tsp::Projection::perspective;
  ImGui::RadioButton("orthographic", &proj, 0);
  note_item("orthographic");
  ImGui::SameLine();
  ImGui::RadioButton("perspective (P)", &proj, 1);
  note_item("perspective (P)");
  if (proj != int(app.state().camera.projection == tsp::Projection::perspective))
    app.push(cmd::SetProjection{proj == 1});
  // Physical proportions from the file's voxel spacing, stretched per axis (e.g. height).
  axis_scale_field(app);  // (Enter applies a typed value, Escape cancels it)
  note_item("axis scale");
  const float half = (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x) / 2;
  if (ImGui::Button("save PNG (S)", ImVec2(half, 0))) app.push(cmd::SavePicture{});
  note_item("save PNG (S)", true);
  ImGui::SameLine();
  if (ImGui::Button("reset view (R)", ImVec2(half, 0))) app.push(cmd::ResetCamera{});
  note_item("reset view (R)", true);
}

namespace {

// The status area at the bottom of the side panel, a fixed kStatusLines high: the playback
// tuning's progress or the rung playing (wrapped: two lines at most), then the last message
// (saved files, fits, errors), wrapped into the lines left and cut short with "..." when longer
// (in full in its tooltip): nothing is cut off at the area's edges, and controls above never
// move when a message comes or goes.
void status_area(PlayerApp& app, float height) {
  ImGui::BeginChild("##status", ImVec2(0, height), true,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  if (const tspgl::PlaybackTuner* t = app.tuning()) {  // runs a slice of each frame
    const int total = std::max(1, t->pictures_total());
    char text[64];
    std::snprintf(text, sizeof text, "tuning playback %d / %d", t->pictures_done(), total);
    ImGui::ProgressBar(float(t->pictures_done()) / float(total), ImVec2(-1, 0), text);
    note_item(text, true);
  } else {
    const std::string rung = app.state().playing ? playback_text(app) : "";
    if (rung.empty()) {
      ImGui::TextUnformatted(" ");
    } else {
      ImGui::TextWrapped("%s", rung.c_str());
      note_wrapped(rung.c_str());
      if (ImGui::IsItemHovered()) tooltip(rung.c_str());
    }
  }
  const std::string shown = fit_lines(app.status_line(), ImGui::GetContentRegionAvail().x,
                                      ImGui::GetContentRegionAvail().y);
  // Errors in red, other messages in amber (an error looked like a saved file's message).
  ImGui::PushStyleColor(ImGuiCol_Text, app.status_is_error() ? ImVec4(1.f, 0.45f, 0.4f, 1.f)
                                                             : ImVec4(1.f, 0.85f, 0.5f, 1.f));
  ImGui::TextWrapped("%s", shown.c_str());
  note_wrapped(shown.c_str());
  ImGui::PopStyleColor();
  ImGui::EndChild();
  if (!app.status_line().empty() && ImGui::IsItemHovered()) tooltip(app.status_line().c_str());
}

// A section's header: open as it starts (default_open), or all open / back to the start after
// the script's `expand on|off`.
bool section(PlayerApp& app, const char* title, bool default_open) {
  if (app.expand_sections != 0)
    ImGui::SetNextItemOpen(app.expand_sections > 0 || default_open, ImGuiCond_Always);
  return ImGui::CollapsingHeader(title, default_open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

// The field shown, for a file with several (each keeps its TF and its caches).
void field_row(PlayerApp& app) {
  const auto& fields = app.viewer().file().fields();
  if (fields.size() <= 1) return;
  const int current = app.viewer().file().field_index();
  const std::string label = fit_label("field");
  if (ImGui::BeginCombo(label.c_str(), fields[std::size_t(current)].c_str())) {
    for (std::size_t k = 0; k < fields.size(); ++k)
      if (ImGui::Selectable(fields[k].c_str(), int(k) == current)) {
        app.push(cmd::ShowField{fields[k]});
      }
    ImGui::EndCombo();
  }
  note_item(label.c_str());
}

// The side panel's sections, common first: the transfer function and its colour range, the
// clip probes, the view; the expert knobs and the statistics collapsed.
void side_sections(PlayerApp& app) {
  field_row(app);
  if (section(app, "Transfer function", true)) tf_section(app);
  if (section(app, "Clip", !app.state().probes.empty())) probes_section(app);
  if (section(app, "View", true)) view_section(app);
  if (section(app, "Rendering (expert)", false)) settings_section(app);
  if (section(app, "Statistics", false)) stats_section(app);
}

// One line (or two) of the statistics, noted for the clipped-item check (ui_items.h): none may
// run past the panel's edge (the sixth walk: "fragments …" was cut off at 1280×800).
[[gnu::format(printf, 2, 3)]] void stat_line(const ImVec4* colour, const char* fmt, ...) {
  char text[256];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(text, sizeof text, fmt, args);
  va_end(args);
  if (colour)
    ImGui::TextColored(*colour, "%s", text);
  else
    ImGui::TextUnformatted(text);
  note_item(text);
}

}  // namespace
void stats_section(PlayerApp& app) {
  // A temporal tolerance that merged steps says which steps' bricks the picture shows.
  const tspgl::FrameReport& lf = app.last;
  if (app.state().settings.tol.temporal > 0 && lf.spans_hi > lf.spans_lo) {  // (at 0 only unchanging data merge)
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
    const ImVec4 amber(1.f, 0.75f, 0.3f, 1.f);
    stat_line(&amber, "%s", note);
  }
  std::vector<float> ms;
  double sum = 0;
  for (const FrameSample& f : app.history) {
    ms.push_back(float(f.ms));
    sum += f.ms;
  }
  const double mean = ms.empty() ? 0 : sum / double(ms.size());
  stat_line(nullptr, "frame %.1f ms (mean %.1f), %.1f fps", ms.empty() ? 0.0 : double(ms.back()), mean,
              mean > 0 ? 1000.0 / mean : 0.0);
  if (!ms.empty())
    ImGui::PlotLines("##ms", ms.data(), int(ms.size()), 0, "frame ms, last 5 s", 0.f,
                     *std::max_element(ms.begin(), ms.end()) * 1.1f,
                     ImVec2(ImGui::GetContentRegionAvail().x, kHudPlotHeight));
  const tspgl::FrameReport& r = app.last;
  // What the last frame drew and its time (player_refine.cpp): never "holding the target"
  // for a frame that missed it.
  ImGui::TextWrapped("%s", app.lod_line().c_str());
  note_wrapped(app.lod_line().c_str());
  stat_line(nullptr, "render %.1f ms: traversal %.1f, slicing %.1f,\n  upload %.1f, draw %.1f", r.ms,
              r.traversal_ms, r.slicing_ms, r.upload_ms, r.draw_ms);
  const double pixels = std::max(1.0, double(app.layout.view.w) * app.layout.view.h);
  // The picture's fragments: those of the frame that last drew it (a frame that reused the whole
  // image draws none, and said 0 for a picture that plainly shows).
  const double fragments = double(app.picture_fragments());
  // (Two lines: in one it ran past the panel's edge at 1280x800.)
  stat_line(nullptr, "fragments %.2f M (%.2f per pixel),\n  %s%s, spacing %.2g",
            fragments / 1e6, fragments / pixels, r.redrawn_percent == 0 ? "image reused, " : "",
            tspgl::to_string(app.state().settings.compositing), app.state().settings.spacing);
  for (int c = 0; c < tsp::kDrawClassCount; ++c)
    stat_line(nullptr, "%-15s %5.1f %%", kClassNames[c], r.class_percent[std::size_t(c)]);
  stat_line(nullptr, "textures %lld resident, %.1f MiB", static_cast<long long>(r.textures_resident),
              double(r.texture_bytes) / kBytesPerMiB);
  stat_line(nullptr, "uploaded this frame %.2f MiB", double(r.bytes_uploaded) / kBytesPerMiB);
  const ImVec4 waiting(1, 0.8f, 0.2f, 1);
  if (!r.complete())
    stat_line(&waiting, "%lld textures wait for later frames (flat meanwhile)",
                       static_cast<long long>(r.deferred_textures));
  stat_line(nullptr, "metric recompute %.2f ms (%lld nodes)", app.viewer().metric_ms(),
              static_cast<long long>(app.viewer().metric_evaluations()));
  const tsp::BrickCacheStats b = app.viewer().renderer().brick_cache().stats();
  stat_line(nullptr, "bricks in RAM %lld (%.1f MiB)\n  %lld hits, %lld misses, %lld prefetched",
              static_cast<long long>(b.resident_count), double(b.resident_bytes) / kBytesPerMiB,
              static_cast<long long>(b.hits), static_cast<long long>(b.misses),
              static_cast<long long>(b.prefetched));
}

void PlayerApp::draw_ui() {
  begin_ui_items();
  if (state_.panels) {
    if (layout.docked) {
      // One side panel of collapsible sections beside the volume, the timeline under it.
      place(layout.side);
      ImGui::Begin("##side", nullptr, kDockedFlags);
      // The sections scroll above a status area of fixed height at the bottom.
      const float status_h = float(kStatusLines) * ImGui::GetTextLineHeightWithSpacing() +
                             2 * ImGui::GetStyle().WindowPadding.y;
      ImGui::BeginChild("##sections", ImVec2(0, -(status_h + ImGui::GetStyle().ItemSpacing.y)));
      side_sections(*this);
      ImGui::EndChild();
      status_area(*this, status_h);
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
      view_section(*this);
      if (section(*this, "Rendering (expert)", false)) settings_section(*this);
      status_area(*this, float(kStatusLines) * ImGui::GetTextLineHeightWithSpacing() +
                             2 * ImGui::GetStyle().WindowPadding.y);
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
  expand_sections = 0;  // (applied once)
  help(*this);
  // Last, after every window that may appear this frame: Dear ImGui 1.86 aborts ("ImGui::Begin:
  // Assertion `blocking_modal != NULL'") when a window appears after a modal begun for the first
  // time in the same frame — File > Open's progress dialog opened in the first frames, before
  // the panels had appeared (issue 28).
  if (state_.panels) menu_and_dialogs(*this);
}

}  // namespace tspplayer
