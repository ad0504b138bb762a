// The player's clip probes (issue 14; docs/player.md "Probes"): the list the UI and the script
// edit, handed to the renderer when it changes; a mouse gizmo for the selected probe (ctrl+drag
// moves it in the view plane, ctrl+wheel resizes it or moves a plane along its normal, alt+drag
// turns a plane or a box); outlines over the volume.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>

#include "player/player_app.h"
#include "player/player_ui.h"
#include "player/ui_items.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {

constexpr double kTurnDegPerPixel = 0.4;
constexpr double kResizePerNotch = 1.1;
constexpr double kPlaneStepPerNotch = 0.02;  // of the volume's diagonal
constexpr ImU32 kSelectedColour = IM_COL32(255, 220, 60, 230);
constexpr ImU32 kProbeColour = IM_COL32(90, 220, 255, 200);
constexpr const char* kKindNames[] = {"plane", "sphere", "box"};
constexpr const char* kOpNames[] = {"intersect", "union", "subtract"};

using Vec = std::array<double, 3>;

glm::dvec3 g(const Vec& v) { return {v[0], v[1], v[2]}; }
Vec a(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// Physical ↔ sample coordinates of the file's grid.
struct Grid {
  glm::dvec3 origin, spacing;
  glm::dvec3 to_sample(const glm::dvec3& p) const { return (p - origin) / spacing; }
  glm::dvec3 to_phys(const glm::dvec3& q) const { return origin + spacing * q; }
};

Grid grid_of(const tsp::TspFile& f) {
  return {g(f.metadata().origin), g(f.metadata().spacing)};
}

// A physical point projected to window pixels of the view (false behind the eye).
bool project(const tsp::Camera& cam, const Grid& grid, const WindowRect& v, const glm::dvec3& p,
             ImVec2& out) {
  const glm::dvec4 q = cam.view_projection() * glm::dvec4(grid.to_sample(p), 1.0);
  if (q.w <= 1e-9) return false;
  out = ImVec2(float(v.x + (q.x / q.w * 0.5 + 0.5) * v.w), float(v.y + (0.5 - q.y / q.w * 0.5) * v.h));
  return true;
}

// The physical displacement a mouse move of (dx, dy) pixels makes at physical point p, in the
// view plane there.
glm::dvec3 drag_displacement(const tsp::Camera& cam, const Grid& grid, const WindowRect& v,
                             const glm::dvec3& p, float dx, float dy) {
  const glm::dmat4 vp = cam.view_projection(), inv = glm::inverse(vp);
  const glm::dvec4 q = vp * glm::dvec4(grid.to_sample(p), 1.0);
  const glm::dvec3 ndc = glm::dvec3(q) / q.w;
  const glm::dvec3 moved = ndc + glm::dvec3(2.0 * dx / std::max(1, v.w), -2.0 * dy / std::max(1, v.h), 0);
  const glm::dvec4 back = inv * glm::dvec4(moved, 1.0);
  return grid.to_phys(glm::dvec3(back) / back.w) - p;
}

// The view's right and up directions in physical space (unit).
std::pair<glm::dvec3, glm::dvec3> view_axes(const tsp::Camera& cam, const Grid& grid) {
  const glm::dmat4 inv = glm::inverse(cam.view());
  const glm::dvec3 r = grid.spacing * glm::dvec3(inv * glm::dvec4(1, 0, 0, 0));
  const glm::dvec3 u = grid.spacing * glm::dvec3(inv * glm::dvec4(0, 1, 0, 0));
  return {glm::normalize(r), glm::normalize(u)};
}

glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& axis, double deg) {
  const double t = deg * 3.14159265358979323846 / 180, c = std::cos(t), s = std::sin(t);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1 - c);
}

// The physical box of the volume.
std::pair<glm::dvec3, glm::dvec3> volume_box(const tsp::TspFile& f, const Grid& grid) {
  const tsp::Dims d = f.tree().octree().dims();
  return {grid.origin, grid.to_phys(glm::dvec3(d.x - 1, d.y - 1, d.z - 1))};
}

}  // namespace

tsp::Probe PlayerApp::default_probe(tsp::Probe::Kind kind) const {
  const Grid grid = grid_of(viewer_->file());
  const auto [lo, hi] = volume_box(viewer_->file(), grid);
  const glm::dvec3 c = 0.5 * (lo + hi), ext = hi - lo;
  tsp::Probe p;
  p.kind = kind;
  if (kind == tsp::Probe::Kind::plane) {  // through the centre, keeping the lower x half
    p.centre = {1, 0, 0};
    p.radius = c.x;
  } else if (kind == tsp::Probe::Kind::sphere) {
    p.centre = a(c);
    p.radius = 0.3 * std::min({ext.x, ext.y, ext.z}) + 1e-9;
  } else {
    p.centre = a(c);
    p.size = a(0.25 * ext + glm::dvec3(1e-9));
  }
  return p;
}

void PlayerApp::add_probe(const tsp::Probe& p) {
  if (int(state_.probes.size()) >= tsp::ClipRegion::kMaxProbes) {
    status = "at most " + std::to_string(tsp::ClipRegion::kMaxProbes) + " probes";
    return;
  }
  state_.probes.push_back(p);
  probe_selected_ = int(state_.probes.size()) - 1;
  probes_changed();
}

void PlayerApp::apply_probes() {
  if (probe_version == applied_probe_version_ && tf.version() == applied_probe_tf_) return;
  try {
    const tsp::ClipRegion clip(state_.probes, state_.probe_op, viewer_->file().metadata().origin, viewer_->file().metadata().spacing);
    viewer_->renderer().set_clip(clip, state_.probe_surface && !state_.probes.empty()
                                 ? std::optional<tsp::TransferFunction>(tf)
                                 : std::nullopt);
  } catch (const tsp::Error& e) {  // (the UI keeps values valid; a script may not)
    status = e.what();
    state_.probes.clear();
    viewer_->renderer().set_clip(tsp::ClipRegion{}, std::nullopt);
  }
  applied_probe_version_ = probe_version;
  applied_probe_tf_ = tf.version();
}

bool PlayerApp::probe_gizmo(const tsp::Camera& cam) {
  const ImGuiIO& io = ImGui::GetIO();
  if (probe_selected_ < 0 || probe_selected_ >= int(state_.probes.size()) || !(io.KeyCtrl || io.KeyAlt))
    return false;
  tsp::Probe& p = state_.probes[std::size_t(probe_selected_)];
  const Grid grid = grid_of(viewer_->file());
  const auto [lo, hi] = volume_box(viewer_->file(), grid);
  const glm::dvec3 vc = 0.5 * (lo + hi);
  const bool plane = p.kind == tsp::Probe::Kind::plane;
  // A plane's handle: its point nearest the volume's centre.
  const glm::dvec3 at = plane ? vc + (p.radius - glm::dot(g(p.centre), vc)) * g(p.centre) : g(p.centre);
  bool changed = false;
  if (io.MouseDown[0] && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    if (io.KeyCtrl) {  // move in the view plane
      const glm::dvec3 d = drag_displacement(cam, grid, layout.view, at, io.MouseDelta.x, io.MouseDelta.y);
      if (plane)
        p.radius += glm::dot(g(p.centre), d);
      else
        p.centre = a(g(p.centre) + d);
    } else {  // alt: turn
      const auto [right, up] = view_axes(cam, grid);
      if (plane) {
        glm::dvec3 n = rotate(g(p.centre), up, io.MouseDelta.x * kTurnDegPerPixel);
        n = glm::normalize(rotate(n, right, io.MouseDelta.y * kTurnDegPerPixel));
        p.centre = a(n);
        p.radius = glm::dot(n, at);  // turning about the handle
      } else if (p.kind == tsp::Probe::Kind::box) {
        p.angles[2] += io.MouseDelta.x * kTurnDegPerPixel;
        p.angles[0] += io.MouseDelta.y * kTurnDegPerPixel;
      }
    }
    changed = true;
  }
  if (io.KeyCtrl && io.MouseWheel != 0) {
    const double f = std::pow(kResizePerNotch, io.MouseWheel);
    if (plane)
      p.radius += io.MouseWheel * kPlaneStepPerNotch * glm::length(hi - lo);
    else if (p.kind == tsp::Probe::Kind::sphere)
      p.radius *= f;
    else
      for (double& h : p.size) h *= f;
    changed = true;
  }
  if (changed) probes_changed();
  return io.MouseDown[0] || io.MouseWheel != 0;
}

void PlayerApp::draw_probe_overlay(const tsp::Camera& cam) {
  if (state_.probes.empty()) return;
  const Grid grid = grid_of(viewer_->file());
  const WindowRect& v = layout.view;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  dl->PushClipRect(ImVec2(float(v.x), float(v.y)), ImVec2(float(v.x + v.w), float(v.y + v.h)), false);
  const auto [lo, hi] = volume_box(viewer_->file(), grid);
  for (std::size_t i = 0; i < state_.probes.size(); ++i) {
    const tsp::Probe& p = state_.probes[i];
    const ImU32 col = int(i) == probe_selected_ ? kSelectedColour : kProbeColour;
    if (p.kind == tsp::Probe::Kind::sphere) {
      ImVec2 c, e;
      const auto [right, up] = view_axes(cam, grid);
      if (project(cam, grid, v, g(p.centre), c) &&
          project(cam, grid, v, g(p.centre) + p.radius * right, e))
        dl->AddCircle(c, std::hypot(e.x - c.x, e.y - c.y), col, 48, 1.5f);
    } else if (p.kind == tsp::Probe::Kind::box) {
      const tsp::ClipRegion one({p}, tsp::ProbeOp::intersect, {0, 0, 0}, {1, 1, 1});
      const auto& r = one.rotations()[0];  // physical → box frame; its transpose back
      ImVec2 q[8];
      bool ok = true;
      for (int c = 0; c < 8; ++c) {
        const glm::dvec3 l(c & 1 ? p.size[0] : -p.size[0], c & 2 ? p.size[1] : -p.size[1],
                           c & 4 ? p.size[2] : -p.size[2]);
        const glm::dvec3 w(r[0] * l.x + r[3] * l.y + r[6] * l.z, r[1] * l.x + r[4] * l.y + r[7] * l.z,
                           r[2] * l.x + r[5] * l.y + r[8] * l.z);
        ok &= project(cam, grid, v, g(p.centre) + w, q[c]);
      }
      if (ok)
        for (int c = 0; c < 8; ++c)
          for (int ax = 0; ax < 3; ++ax)
            if (!(c & (1 << ax))) dl->AddLine(q[c], q[c | (1 << ax)], col, 1.5f);
    } else {
      // The plane's polygon inside the volume: where the box's 12 edges cross it.
      const glm::dvec3 n = g(p.centre);
      std::vector<glm::dvec3> pts;
      for (int c = 0; c < 8; ++c)
        for (int ax = 0; ax < 3; ++ax) {
          if (c & (1 << ax)) continue;
          const glm::dvec3 e0(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
          glm::dvec3 e1 = e0;
          e1[ax] = hi[ax];
          const double s0 = glm::dot(n, e0) - p.radius, s1 = glm::dot(n, e1) - p.radius;
          if ((s0 < 0) != (s1 < 0)) pts.push_back(e0 + (e1 - e0) * (s0 / (s0 - s1)));
        }
      if (pts.size() < 3) continue;
      glm::dvec3 mid(0);
      for (const auto& q : pts) mid += q / double(pts.size());
      const glm::dvec3 u = glm::normalize(pts[0] - mid), w = glm::cross(n, u);
      std::sort(pts.begin(), pts.end(), [&](const glm::dvec3& x, const glm::dvec3& y) {
        return std::atan2(glm::dot(x - mid, w), glm::dot(x - mid, u)) <
               std::atan2(glm::dot(y - mid, w), glm::dot(y - mid, u));
      });
      std::vector<ImVec2> poly(pts.size());
      bool ok = true;
      for (std::size_t k = 0; k < pts.size(); ++k) ok &= project(cam, grid, v, pts[k], poly[k]);
      if (ok) dl->AddPolyline(poly.data(), int(poly.size()), col, ImDrawFlags_Closed, 1.5f);
    }
  }
  dl->PopClipRect();
}

void probes_section(PlayerApp& app) {
  int op = int(app.state().probe_op);
  ImGui::SetNextItemWidth(120);
  if (ImGui::Combo("combine", &op, kOpNames, IM_ARRAYSIZE(kOpNames)))
    app.push(cmd::SetProbeOp{tsp::ProbeOp(op)});
  note_item("combine");
  ImGui::SameLine();
  if (bool on = app.state().probe_surface; ImGui::Checkbox("surface", &on))
    app.push(cmd::ProbeSurface{on});
  note_item("surface");
  if (ImGui::IsItemHovered())
    tooltip("draw the probe's surface opaque, coloured by the data through the TF");
  for (int k = 0; k < 3; ++k) {
    if (k) ImGui::SameLine();
    const std::string add = std::string("+ ") + kKindNames[k];
    if (ImGui::Button(add.c_str())) app.push(cmd::AddProbe{app.default_probe(tsp::Probe::Kind(k))});
    note_item(add.c_str(), true);
  }
  int remove = -1;
  for (std::size_t i = 0; i < app.state().probes.size(); ++i) {
    tsp::Probe p = app.state().probes[i];  // (edits go back as a command)
    ImGui::PushID(int(i));
    char title[32];
    std::snprintf(title, sizeof title, "%zu: %s", i + 1, kKindNames[int(p.kind)]);
    if (ImGui::Selectable(title, app.selected_probe() == int(i))) app.push(cmd::SelectProbe{int(i)});
    bool edited = false;
    float c[3] = {float(p.centre[0]), float(p.centre[1]), float(p.centre[2])};
    float r = float(p.radius);
    const float drag_step = 0.005f * float(std::max({std::fabs(c[0]), std::fabs(c[1]), std::fabs(c[2]), 1.f}));
    if (p.kind == tsp::Probe::Kind::plane) {
      if (ImGui::DragFloat3("normal", c, 0.01f)) {
        const double n = std::hypot(c[0], c[1], c[2]);
        if (n > 0) {
          p.centre = {c[0] / n, c[1] / n, c[2] / n};
          edited = true;
        }
      }
      edited |= ImGui::DragFloat("offset", &r, drag_step);
      p.radius = r;
    } else {
      if (ImGui::DragFloat3("centre", c, drag_step)) {
        p.centre = {c[0], c[1], c[2]};
        edited = true;
      }
      if (p.kind == tsp::Probe::Kind::sphere && ImGui::DragFloat("radius", &r, drag_step, 1e-6f, 1e9f)) {
        p.radius = std::max(1e-6, double(r));
        edited = true;
      }
      if (p.kind == tsp::Probe::Kind::box) {
        float h[3] = {float(p.size[0]), float(p.size[1]), float(p.size[2])};
        float t[3] = {float(p.angles[0]), float(p.angles[1]), float(p.angles[2])};
        if (ImGui::DragFloat3("half size", h, drag_step, 1e-6f, 1e9f)) {
          p.size = {std::max(1e-6, double(h[0])), std::max(1e-6, double(h[1])), std::max(1e-6, double(h[2]))};
          edited = true;
        }
        if (ImGui::DragFloat3("angles", t, 0.5f)) {
          p.angles = {t[0], t[1], t[2]};
          edited = true;
        }
      }
    }
    if (ImGui::SmallButton("remove")) remove = int(i);
    if (edited) app.push(cmd::EditProbe{int(i), p});
    ImGui::PopID();
  }
  if (remove >= 0) app.push(cmd::RemoveProbe{remove});
  if (!app.state().probes.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("selected probe: ctrl+drag moves it, ctrl+wheel resizes (a plane: moves it "
                       "along its normal), alt+drag turns a plane or a box");
    ImGui::PopStyleColor();
  }
}

}  // namespace tspplayer
