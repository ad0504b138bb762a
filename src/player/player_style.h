// The window's Dear ImGui style: the dark colours, with opaque popups (issue 47 walk 5: the open
// colour-map list showed the buttons under it through its 94 % background).
#pragma once

struct ImGuiStyle;

namespace tspplayer {

/// Sets style to the player's look: ImGui's dark colours, popups, menus and tooltips opaque.
/// Never throws.
void apply_player_style(ImGuiStyle& style);

}  // namespace tspplayer
