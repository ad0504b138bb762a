// The player's Dear ImGui sections, drawn into whatever window the layout gives them (the docked
// side panel or floating windows). Internal to src/player.
#pragma once
#include <string>

namespace tspplayer {

class PlayerApp;

/// The expert knobs: metric, tolerances (with what they buy), quality knobs, LOD, caches
/// (player_settings_ui.cpp).
void settings_section(PlayerApp& app);
/// What the view shows: annotations, projection, axis scale, save PNG, reset (player_ui.cpp).
void view_section(PlayerApp& app);
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
/// The TF editor's file path (its load / save as row; File > Save transfer function as offers
/// it): the panels' own, not the player's.
std::string& tf_file_path();
/// Opens a File menu dialog at the next frame with the panels shown, as its menu item does:
/// which is open, save-tf, record or save-session; close closes the one open (script `dialog`).
void show_dialog(const std::string& which);
/// The label to give the next item so that label and item fit the window: label itself with the
/// item as wide as the rest of the row allows, or, when that leaves the item less than
/// min_item_w pixels, the label on a line of its own above an item the row's width ("##"
/// label). The item is recorded for the clipped-label check after it is drawn (note_item).
std::string fit_label(const char* label, float min_item_w = 110.f);
/// A tooltip for the last item, wrapped to stay inside the window. Never throws.
void tooltip(const char* text);
/// text as it fits in width × height pixels wrapped (Dear ImGui's TextWrapped), cut short with
/// "..." when it does not. Never throws but bad_alloc.
std::string fit_lines(const std::string& text, float width, float height);

}  // namespace tspplayer
