#include "player/axis_scale_field.h"

#include <imgui.h>
#include <imgui_internal.h>  // TempInputIsActive: whether a drag field is being typed into

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>

#include "player/player_app.h"

namespace tspplayer {

namespace {
constexpr float kMinScale = 0.05f, kMaxScale = 100.f;
}  // namespace

void axis_scale_field(PlayerApp& app) {
  // A value typed into an axis' field, applied when the field is left (not key by key: the view
  // would jump to 3 on the way to 30, and Escape would then have to undo what was shown).
  static std::array<std::optional<float>, 3> typed;
  static std::array<float, 4> traced{-1, -1, -1, -1};
  const ImGuiStyle& style = ImGui::GetStyle();
  const float width = std::max(20.f, (ImGui::CalcItemWidth() - 2 * style.ItemInnerSpacing.x) / 3);
  const bool escape = ImGui::IsKeyPressedMap(ImGuiKey_Escape, false);
  ImGui::PushID("axis scale");
  for (int a = 0; a < 3; ++a) {
    if (a) ImGui::SameLine(0, style.ItemInnerSpacing.x);
    ImGui::PushID(a);
    ImGui::SetNextItemWidth(width);
    float v = float(app.scale()[std::size_t(a)]);
    const bool changed = ImGui::DragFloat("##k", &v, 0.02f, kMinScale, kMaxScale, "%.2f",
                                          ImGuiSliderFlags_Logarithmic);
    const bool typing = ImGui::TempInputIsActive(ImGui::GetItemID());
    std::array<double, 3> next = app.scale();
    bool pushed = false;  // (Enter applies the typed value once: not as a drag and again here)
    if (changed && typing) {
      typed[std::size_t(a)] = v;
    } else if (changed && !escape) {  // dragged (Escape's revert of a typed value: nothing)
      next[std::size_t(a)] = std::clamp(v, kMinScale, kMaxScale);
      app.push(cmd::SetScale{next});
      pushed = true;
    }
    if (ImGui::IsItemDeactivated()) {
      const std::optional<float> t = typed[std::size_t(a)];
      // (A value the frame before applied already, as Enter's frame may: not again.)
      if (t && !escape && !pushed &&
          double(std::clamp(*t, kMinScale, kMaxScale)) != app.scale()[std::size_t(a)]) {
        next[std::size_t(a)] = std::clamp(*t, kMinScale, kMaxScale);
        app.push(cmd::SetScale{next});
      }
      typed[std::size_t(a)].reset();
    }
    if (a == 2 && app.tracing()) {
      const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
      const std::array<float, 4> r{lo.x, lo.y, hi.x - lo.x, hi.y - lo.y};
      if (r != traced) {
        traced = r;
        std::printf("trace: axis scale field %.0f %.0f %.0f %.0f\n", r[0], r[1], r[2], r[3]);
        std::fflush(stdout);
      }
    }
    ImGui::PopID();
  }
  ImGui::PopID();
  ImGui::SameLine(0, style.ItemInnerSpacing.x);
  ImGui::TextUnformatted("axis scale");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Stretch per axis (x, y, z) of the physical proportions; a flat domain\n"
                      "opens stretched in z (named over the picture, \"z × 30\").\n"
                      "Drag, or Ctrl+click and type: Enter applies, Escape cancels.");
}

}  // namespace tspplayer
