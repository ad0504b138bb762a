// The window's Dear ImGui style (player/player_style.h): popups are opaque (issue 47 walk 5: the
// open colour-map list showed the buttons under it through ImGui's 94 % popup background).
#include "player/player_style.h"

#include <gtest/gtest.h>
#include <imgui.h>

namespace {

TEST(PlayerStyle, PopupsMenusAndTooltipsAreOpaque) {
  ImGuiContext* c = ImGui::CreateContext();
  ImGuiStyle style;
  tspplayer::apply_player_style(style);
  // (Combo lists, menus, modal dialogs and tooltips all draw on PopupBg.)
  EXPECT_EQ(style.Colors[ImGuiCol_PopupBg].w, 1.f);
  EXPECT_EQ(style.Alpha, 1.f);
  // The rest is ImGui's dark look.
  ImGuiStyle dark;
  ImGui::StyleColorsDark(&dark);
  EXPECT_EQ(style.Colors[ImGuiCol_WindowBg].x, dark.Colors[ImGuiCol_WindowBg].x);
  EXPECT_EQ(style.Colors[ImGuiCol_Button].z, dark.Colors[ImGuiCol_Button].z);
  ImGui::DestroyContext(c);
}

}  // namespace
