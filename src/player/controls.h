// The player's keys and mouse actions: one table for the F1 overlay, `play --help` and the docs.
#pragma once

namespace tspplayer {

/// One input and what it does.
struct Control {
  const char* input;
  const char* action;
};

/// Every key and mouse action of the player, in the order they are listed.
inline constexpr Control kControls[] = {
    {"space", "play / pause"},
    {"left / right arrow", "previous / next step (pauses)"},
    {"Home / End", "first / last step"},
    {"left drag", "orbit (azimuth, elevation)"},
    {"right or middle drag, shift + left drag", "pan"},
    {"wheel", "zoom"},
    {"R", "reset the camera (view, zoom, pan, projection)"},
    {"P", "orthographic / perspective"},
    {"S", "save the current frame as INPUT_FIELD_step_NNNN.png (-2, -3, ... when taken)"},
    {"L", "show / hide the LOD cut (node boxes coloured by level)"},
    {"double-click", "set the LOD centre of attention"},
    {"Tab", "show / hide the panels (hidden: the volume fills the window)"},
    {"F1 or ?", "show / hide this list"},
    {"TF editor: drag a handle", "move a point (value, opacity)"},
    {"TF editor: double-click / right-click", "add a point / remove a point"},
    {"Ctrl+O", "File > Open (its path field takes the keys)"},
    {"Ctrl+A (in a text field)", "select all of its text"},
    {"Ctrl+Q", "quit (as File > Quit)"},
};

}  // namespace tspplayer
