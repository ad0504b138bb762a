#include "player/player_style.h"

#include <imgui.h>

namespace tspplayer {

void apply_player_style(ImGuiStyle& style) {
  ImGui::StyleColorsDark(&style);
  // Combo lists, menus, modal dialogs and tooltips (all drawn on PopupBg) cover what lies
  // under them: a list over buttons must not read as buttons.
  style.Colors[ImGuiCol_PopupBg].w = 1.f;
}

}  // namespace tspplayer
