// The player's LOD cut (docs/player.md "Level of detail"): while the view, the step, the TF or
// playback change, the cut holds the target frame rate (frame time minus the UI's share); once
// nothing changed for kIdleDelaySeconds it refines every node, kIdleSplitsPerFrame a frame, at
// full render size, so the picture returns to full quality within a few frames.
#include "player/player_app.h"
#include "tsp/report/ticks.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <glm/glm.hpp>

#include "jobs/annotate.h"
#include "tsp/frame/exaggeration.h"

namespace tspplayer {

namespace {
// The live colour legend: its height as a share of the view's (at least kMinLegendPx), its bar's
// width, its distance from the view's right edge (room for the tick labels), and its ticks.
constexpr float kLegendHeightShare = 0.4f, kMinLegendPx = 60, kLegendWidthPx = 14,
                kLegendRightPx = 80;
constexpr int kLegendTicks = 5;
// With the surface's bar: each bar's share of the view's height, the title's height above a
// bar, the gap between the bars, and the least pixels per tick.
constexpr float kTwoLegendsShare = 0.3f, kLegendTitlePx = 20, kLegendGapPx = 6, kLegendTickPx = 24;
// Colours of the cut overlay by LOD level (level 0 first), RGBA.
constexpr ImU32 kLevelColours[] = {IM_COL32(80, 220, 80, 200), IM_COL32(240, 220, 60, 200),
                                   IM_COL32(250, 140, 40, 200), IM_COL32(240, 60, 60, 200),
                                   IM_COL32(200, 60, 240, 200), IM_COL32(80, 120, 255, 200)};
}  // namespace

void PlayerApp::set_lod(bool on) {
  state_.lod_on = on;
  viewer_->reset_lod();  // a new controller when it is turned on again
}

tspgl::LodSpec PlayerApp::lod_spec(double now_s) {
  // (Playing at a quality target: the tuned rung's level, or the provisional rung's.)
  const tspgl::Rung* r = state_.playing && state_.quality > 0 ? rung_drawn() : nullptr;
  return lod_loop_.next(
      state_, {tf.version(), probe_version, r ? r->lod_level : 0, !refine_by_cut()}, now_s);
}

void PlayerApp::lod_drawn(const std::optional<tsp::LodFrameStats>& stats, double now_s) {
  lod_loop_.drawn(stats);
  if (!state_.lod_on) return;
  lod_loop_.note_quality(full_quality(), now_s);
}

bool PlayerApp::full_quality() const {
  // A selection filter's cut is the picture asked for: nothing is left to refine once drawn.
  if (state_.lod_on && state_.lod_filter.kind != tsp::LodFilter::error) return true;
  if (!state_.lod_on) return true;
  // Refined in bands (player_refine.cpp): full once the last band is drawn.
  if (refine_on_) return stage_ == "full";
  // (With the mesh's surface the cut itself refines.)
  return lod_loop_.cut_full_quality();
}

void PlayerApp::measured_lod(double render_ms, double frame_ms) {
  lod_loop_.measured(render_ms, frame_ms);
}

void PlayerApp::set_focus_at(double x, double y) {
  const tsp::Dims d = viewer_->file().tree().octree().dims();
  lod_loop_.focus_on(focus_at(tsp::Camera(d, state_.camera), d, x, y), clock_.seconds());
}

namespace {

// Corner c (bit a: high along axis a) of box, projected to window pixels of the view v; false
// behind the eye.
bool corner(const glm::dmat4& vp, const tsp::Aabb& box, int c, const WindowRect& v, ImVec2& out) {
  const glm::dvec4 q = vp * glm::dvec4(c & 1 ? box.hi[0] : box.lo[0], c & 2 ? box.hi[1] : box.lo[1],
                                        c & 4 ? box.hi[2] : box.lo[2], 1.0);
  if (q.w <= 1e-9) return false;
  out = ImVec2(float(v.x + (q.x / q.w * 0.5 + 0.5) * v.w),
               float(v.y + (0.5 - q.y / q.w * 0.5) * v.h));
  return true;
}

// The background draw list, clipped to the view (the docked panels lie beside it).
ImDrawList* view_draw_list(const WindowRect& v) {
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  dl->PushClipRect(ImVec2(float(v.x), float(v.y)), ImVec2(float(v.x + v.w), float(v.y + v.h)),
                   false);
  return dl;
}

// One colour bar of the legend at the view's right edge, as render --annotate draws it: tf's
// colours (opaque) at (x0, y0), h tall, low at the bottom, `ticks` value ticks, the title above
// (ending left of `right`, the view's right edge).
void draw_legend(ImDrawList* dl, float x0, float y0, float h, const tsp::TransferFunction& tf,
                 const std::string& title, int ticks, float right) {
  const tsp::ValueRange dom = tf.domain();
  for (int r = 0; r < int(h); ++r) {
    const double value = dom.hi - (dom.hi - dom.lo) * r / std::max(1.0, double(h) - 1);
    const tsp::Rgba c = tf.lookup(value);
    const auto u8 = [](float x) { return int(std::clamp(x, 0.f, 1.f) * 255 + 0.5f); };
    dl->AddRectFilled(ImVec2(x0, y0 + float(r)), ImVec2(x0 + kLegendWidthPx, y0 + float(r) + 1),
                      IM_COL32(u8(c.r), u8(c.g), u8(c.b), 255));
  }
  const ImU32 text = IM_COL32(235, 235, 235, 255);
  dl->AddRect(ImVec2(x0 - 1, y0 - 1), ImVec2(x0 + kLegendWidthPx + 1, y0 + h + 1), text);
  // Round values (0.2 0.4 …, tsp/report/ticks.h) at their places along the bar, as the
  // export's legend (jobs/annotate.cpp).
  const std::vector<double> values = tsp::nice_ticks(dom.lo, dom.hi, ticks + 1);
  const double step = values.size() > 1 ? values[1] - values[0] : 1.0;
  for (double value : values) {
    const double u = dom.hi > dom.lo ? (dom.hi - value) / (dom.hi - dom.lo) : 0.0;
    const float y = y0 + (h - 1) * float(u);
    dl->AddLine(ImVec2(x0 + kLegendWidthPx, y), ImVec2(x0 + kLegendWidthPx + 4, y), text);
    dl->AddText(ImVec2(x0 + kLegendWidthPx + 6, y - 7), text, tsp::tick_text(value, step).c_str());
  }
  // (Moved left as far as a long title, "surface: alpha.water", needs to end inside the view.)
  if (!title.empty())
    dl->AddText(ImVec2(std::min(x0 - 4, right - 4 - ImGui::CalcTextSize(title.c_str()).x),
                       y0 - kLegendTitlePx),
                text, title.c_str());
}

// The legend: the volume's bar, and with a surface its map in a second bar below it ("surface:
// FIELD"), in the same column (as jobs/annotate.cpp).
void draw_legends(ImDrawList* dl, const WindowRect& v, const tsp::TransferFunction& tf,
                  const std::string& field, const tspgl::MeshSurface* surface) {
  const float right = float(v.x + v.w), x0 = right - kLegendRightPx;
  if (!surface) {
    const float h = std::max(kMinLegendPx, float(v.h) * kLegendHeightShare);
    draw_legend(dl, x0, float(v.y) + (float(v.h) - h) * 0.5f, h, tf, field, kLegendTicks, right);
    return;
  }
  // (both within the view: a short view gets shorter bars)
  const float h = std::min(std::max(kMinLegendPx * 0.5f, float(v.h) * kTwoLegendsShare),
                           (float(v.h) - 2 * kLegendTitlePx - kLegendGapPx - 8) * 0.5f);
  const float y0 = float(v.y) + std::max(kLegendTitlePx, (float(v.h) - 2 * h - kLegendTitlePx -
                                                          kLegendGapPx) * 0.5f);
  const int ticks = std::clamp(int(h / kLegendTickPx), 1, kLegendTicks);
  draw_legend(dl, x0, y0, h, tf, field, ticks, right);
  draw_legend(dl, x0, y0 + h + kLegendTitlePx + kLegendGapPx, h, surface->tf(),
              "surface: " + surface->field(), ticks, right);
}

}  // namespace

void PlayerApp::draw_annotations(const tsp::Camera& cam) {
  if (!state_.annotations) return;
  const WindowRect& v = layout.view;
  ImDrawList* dl = view_draw_list(v);
  // Crisp one-pixel lines in exactly the outline colour (as render --annotate draws them).
  dl->Flags &= ~ImDrawListFlags_AntiAliasedLines;
  const glm::dmat4 vp = cam.view_projection();
  const tsp::Octree& o = viewer_->file().tree().octree();
  const tsp::Aabb box = tsp::geometric_box(tsp::Box{{0, 0, 0}, {o.dims().x, o.dims().y, o.dims().z}},
                                           o.dims());
  ImVec2 p[8];
  bool ok = true;
  for (int c = 0; c < 8; ++c) ok &= corner(vp, box, c, v, p[c]);
  if (ok) {
    // (With the cut shown its boxes outline the volume in their levels' colours instead.)
    for (int c = 0; c < 8 && !state_.show_cut; ++c)
      for (int a = 0; a < 3; ++a)
        if (!(c & (1 << a))) dl->AddLine(p[c], p[c | (1 << a)], IM_COL32(200, 200, 200, 255));
    // Axes triad at the origin corner: x red, y green, z blue, labelled.
    const double len = 0.25 * std::min({box.hi[0], box.hi[1], box.hi[2]}) + 1;
    const ImU32 cols[3] = {IM_COL32(230, 60, 60, 255), IM_COL32(60, 200, 60, 255),
                           IM_COL32(80, 120, 255, 255)};
    const char* names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      tsp::Aabb tip;
      tip.hi[a] = len;
      ImVec2 e;
      if (!corner(vp, tip, 1 << a, v, e)) continue;
      dl->AddLine(p[0], e, cols[a], 2.f);
      dl->AddText(ImVec2(e.x + 3, e.y - 7), cols[a], names[a]);
    }
  }
  // Step and physical time over the volume, top left: where S, movies and render --annotate
  // put it (jobs/annotate.cpp; it sat top centre in the window, top left in exports).
  const auto& times = viewer_->file().metadata().times;
  char label[96];
  if (times.empty())
    std::snprintf(label, sizeof label, "step %d", state_.step);
  else
    std::snprintf(label, sizeof label, "step %d   t = %s", state_.step,
                  tsp::format_time(times[std::size_t(state_.step)], viewer_->file().metadata().time_units).c_str());
  // A stretched axis is named under it ("z × 30"): heights are not to scale. Both on an opaque
  // box (as the export's caption, jobs/annotate.cpp), so that the outline never crosses them.
  const std::string k = tsp::exaggeration_text(options_.scale);
  const ImVec2 at(float(v.x) + 8, float(v.y) + 8);
  const ImVec2 size1 = ImGui::CalcTextSize(label), size2 = ImGui::CalcTextSize(k.c_str());
  const float line = ImGui::GetFontSize();
  const float pad = 3;
  dl->AddRectFilled(ImVec2(at.x - pad, at.y - pad),
                    ImVec2(at.x + std::max(size1.x, k.empty() ? 0.f : size2.x) + pad,
                           at.y + (k.empty() ? line : 2 * line) + pad),
                    IM_COL32(tspgl::kCaptionBox[0], tspgl::kCaptionBox[1], tspgl::kCaptionBox[2], 255));
  dl->AddText(at, IM_COL32(235, 235, 235, 255), label);
  if (!k.empty()) dl->AddText(ImVec2(at.x, at.y + line), IM_COL32(80, 120, 255, 255), k.c_str());
  draw_legends(dl, v, tf, field(),
               mesh_surface && state_.settings.surface ? &*mesh_surface : nullptr);
  dl->PopClipRect();
}

void PlayerApp::keep_drawn_cut(tsp::LodStops stops) {
  if (state_.show_cut) lod_loop_.keep_cut(stops);
}

void PlayerApp::draw_cut_overlay(const tsp::Camera& cam) {
  if (!state_.show_cut) return;
  // The cut the last frame drew: the adaptive cut while interacting, the playing rung's level,
  // or, paused at full quality (refined in bands) or with LOD off, every leaf at level 0 (it
  // once drew only the adaptive controller's cut, so paused or playing L showed nothing).
  const WindowRect& v = layout.view;
  ImDrawList* dl = view_draw_list(v);
  const glm::dmat4 vp = cam.view_projection();
  const tsp::Octree& o = viewer_->file().tree().octree();
  for (int id = 0; id < o.size(); ++id) {
    if (!in_cut(o, lod_loop_.drawn_cut(), id)) continue;
    const tsp::Aabb box = tsp::geometric_box(o.node(id).box, o.dims());
    ImVec2 p[8];
    bool ok = true;
    for (int c = 0; c < 8; ++c) ok &= corner(vp, box, c, v, p[c]);
    if (!ok) continue;
    const ImU32 col = kLevelColours[std::min<std::size_t>(std::size_t(o.lod_level(id)),
                                                          std::size(kLevelColours) - 1)];
    for (int c = 0; c < 8; ++c)
      for (int a = 0; a < 3; ++a)
        if (!(c & (1 << a))) dl->AddLine(p[c], p[c | (1 << a)], col);
  }
  // What the boxes are, at the view's bottom left (the caption is at the top).
  const std::string text = cut_text(o, lod_loop_.drawn_cut());
  const ImVec2 at(float(v.x) + 8, float(v.y + v.h) - ImGui::GetFontSize() - 8);
  dl->AddRectFilled(ImVec2(at.x - 3, at.y - 3),
                    ImVec2(at.x + ImGui::CalcTextSize(text.c_str()).x + 3,
                           at.y + ImGui::GetFontSize() + 3),
                    IM_COL32(0, 0, 0, 160));
  dl->AddText(at, kLevelColours[0], text.c_str());
  if (tracing() && text != traced_cut_) {
    traced_cut_ = text;
    trace(text);
  }
  dl->PopClipRect();
}

}  // namespace tspplayer
