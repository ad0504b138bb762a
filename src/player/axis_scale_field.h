// The axis-scale field of the Settings panel: three numbers that stretch the view per axis
// (a flat domain opens with its own, "z × 30").
#pragma once

namespace tspplayer {

class PlayerApp;

/// Draws the "axis scale" row: dragging a number stretches the view as it moves; a typed value
/// (Ctrl+click or double-click) applies on Enter or when the field is left, and Escape cancels
/// the edit only (the scale stays as it was). With --trace prints "trace: axis scale field X Y
/// W H" (the z field's rect) when it moves. Never throws.
void axis_scale_field(PlayerApp& app);

}  // namespace tspplayer
