// The player's Dear ImGui sections, drawn into whatever window the layout gives them (the docked
// side panel or floating windows). Internal to src/player.
#pragma once

namespace tspplayer {

class PlayerApp;

/// Metric, tolerances (with their units), quality knobs, LOD, caches, view (player_ui.cpp).
void settings_section(PlayerApp& app);
/// Frame times, the renderer's split, fragments, classes, caches (player_ui.cpp).
void stats_section(PlayerApp& app);
/// Play controls, the step scrubber and the steps' readiness marks (player_ui.cpp).
void timeline_section(PlayerApp& app);
/// The transfer-function editor (player_tf_editor.cpp).
void tf_section(PlayerApp& app);
/// The clip probes: list, parameters, combination, surface (player_probes.cpp).
void probes_section(PlayerApp& app);
/// The main menu bar and the dialogs it opens: File > Open, save TF as, record (player_menu.cpp).
void menu_and_dialogs(PlayerApp& app);

}  // namespace tspplayer
