// A slider's value text beside its grab, on its frame (issue 47 walk 5: the scrubber's and the
// speed slider's grabs covered the text Dear ImGui centres on the frame).
#pragma once

namespace tspplayer {

/// A slider grab's left and right edges, in pixels.
struct GrabSpan {
  float lo = 0, hi = 0;
};

/// The grab of a slider over the frame [x0, x1] as Dear ImGui 1.86 places it: t in [0, 1] the
/// value's share of the range, grab its width (an int slider of n values: the usable width / n,
/// at least the style's GrabMinSize; a float slider: GrabMinSize), 2 pixels of padding at each
/// end. Never throws.
GrabSpan slider_grab(float x0, float x1, double t, float grab);
/// The grab width of an int slider of values lo..hi over the frame [x0, x1] (ImGui 1.86).
float int_slider_grab_width(float x0, float x1, int lo, int hi, float grab_min);
/// Where text of width text_w starts so the grab cannot cover it: centred in the wider of the
/// frame's two sides of the grab when it fits there, else against the frame's edge on that
/// side (what does not fit is clipped at the grab). Never throws.
float text_beside_grab(float x0, float x1, GrabSpan grab, float text_w);
/// False when neither side of the grab has room for a third of text_w (a slider of one value:
/// its grab fills the frame): the text is then drawn over the grab, centred on the frame, as
/// Dear ImGui draws it. Never throws.
bool room_beside_grab(float x0, float x1, GrabSpan grab, float text_w);

}  // namespace tspplayer
