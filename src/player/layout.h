// Where the player puts the volume and its panels in the window, and the TF editor's opacity
// axis: pure functions of sizes and values (no GL, no window), so tests check them directly.
#pragma once

namespace tspplayer {

/// Width of the docked side panel, pixels.
inline constexpr int kSidePanelWidth = 370;
/// Height of the docked timeline, pixels.
inline constexpr int kTimelineHeight = 86;
/// Smallest window that docks the panels beside the volume (at least half of it stays volume);
/// a smaller one shows them floating over the volume.
inline constexpr int kDockMinWidth = 2 * kSidePanelWidth, kDockMinHeight = 4 * kTimelineHeight;
/// Smallest opacity the logarithmic opacity axis shows above zero.
inline constexpr double kLogOpacityFloor = 1e-4;

/// A rectangle of the window in pixels, top-left origin (GLFW's and Dear ImGui's convention).
struct WindowRect {
  int x = 0, y = 0, w = 0, h = 0;
  bool operator==(const WindowRect&) const = default;
};

/// The player's window layout.
struct Layout {
  WindowRect view;      ///< the volume (camera size, screenshots, recordings)
  WindowRect side;      ///< the docked side panel (empty when not docked)
  WindowRect timeline;  ///< the docked timeline (empty when not docked)
  bool docked = false;  ///< panels beside the volume (false: floating over it, or hidden)
};

/// The layout of a width × height window: with panels shown and room to dock them (kDockMin*),
/// the menu bar (menu_height) on top, the side panel on the right, the timeline under the volume
/// and the volume in the rest; otherwise the volume fills the window (floating panels, or none).
/// Sizes are clamped to at least 1 pixel. Never throws.
Layout compute_layout(int width, int height, bool panels, int menu_height);

/// Height of opacity a (in [0, 1]) on the TF editor's axis, in [0, 1]: a itself, or on a log
/// scale from kLogOpacityFloor (0 at the bottom, below the floor too) to 1. Never throws.
double opacity_to_axis(double a, bool log_scale);
/// The inverse of opacity_to_axis (u in [0, 1], clamped); the lowest 1 % of a log axis is 0.
/// Never throws.
double axis_to_opacity(double u, bool log_scale);

}  // namespace tspplayer
