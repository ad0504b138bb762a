// The panels' labelled items as the last frame laid them out (their rectangles, their labels'
// widths and the right edge their window shows), for the clipped-label check: `stats` writes
// them as ui_items, and a test asserts no label is wider than its item nor an item wider than
// its window at 1280×800 and 1920×1080 (docs/player.md "Layout").
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tspplayer {

/// One labelled item of the last frame, in window pixels (top-left origin).
struct UiItem {
  std::string label;       ///< the text shown (before any "##")
  float x = 0, y = 0, w = 0, h = 0;  ///< the item's rectangle
  float text_w = 0;        ///< the label's width
  float inner_w = 0;       ///< room for the label inside the item (a button's frame less padding)
  float clip_right = 0;    ///< the right edge of what its window shows
  float clip_bottom = 0;   ///< the bottom edge of what its window shows
  bool scrolls = true;     ///< its window scrolls (false: an item below clip_bottom is cut off)
};

/// Forgets the last frame's items (called when the panels are drawn again). Never throws.
void begin_ui_items();
/// Records the item Dear ImGui laid out last under its label; framed: the label is drawn inside
/// the item (a button), so it must fit within the frame's padding; reserved: pixels of the item
/// its label cannot use (a combo's arrow). Never throws but bad_alloc.
void note_item(const char* label, bool framed = false, float reserved = 0);
/// Records wrapped text Dear ImGui laid out last (TextWrapped): its width fits by wrapping, its
/// height must fit its window. Never throws but bad_alloc.
void note_wrapped(const char* text);
/// Records the hint a text field shows while empty (InputTextWithHint), laid out last in a
/// frame field_w wide: the hint must fit inside the frame's padding. Never throws but bad_alloc.
void note_hint(const char* hint, float field_w);
/// Records the window Dear ImGui is drawing (a dialog) as the item "dialog: TITLE", its
/// rectangle against the whole window's (clip_right, clip_bottom: the display's size; it does
/// not scroll), so a test can check where a dialog lies. Never throws but bad_alloc.
void note_window(const char* title);
/// The last frame's items.
const std::vector<UiItem>& ui_items();
/// ui_items() as JSON: [{label, x, y, w, h, text_w, inner_w, clip_right, clip_bottom, scrolls}].
nlohmann::json ui_items_json();

}  // namespace tspplayer
