// Annotations drawn into a rendered frame (render --annotate): the volume's outline box, an axes
// triad at its origin corner (x red, y green, z blue), a colour legend of the TF with value ticks,
// and the step (and physical time) as text — on the CPU, over the read-back pixels, with a small
// built-in bitmap font, so headless OSMesa frames carry them too.
#pragma once
#include <optional>
#include <string>

#include "tsp/core/types.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/report/image.h"

namespace tspgl {

/// Pixel colour of the outline box.
inline constexpr unsigned char kOutlineColour[3] = {200, 200, 200};
/// Pixel colour of the opaque box under the caption (step, time, stretch): the outline never
/// crosses the text, and no blend of the text over it is the outline's colour.
inline constexpr unsigned char kCaptionBox[3] = {24, 24, 40};

/// A second colour bar under the volume's: the map of the mesh surface drawn with it (render|play
/// --surface boundary), titled "surface: FIELD". No bar when tf is null.
struct SurfaceLegend {
  const tsp::TransferFunction* tf = nullptr;  ///< the surface's colours (null: no surface)
  std::string field;                          ///< the field the surface shows
};

/// Draws the annotations into img (the frame camera drew, of a volume of dims): outline, axes,
/// legend over the TF's domain titled with field (when not empty), and "step N" (with "  t =
/// TIME" when time, the step's time as tsp::format_time writes it, is given), with `stretch`
/// (an axis exaggeration, "z x 30"; none when empty) under it. The one export look: render
/// --annotate, the player's S and its movies. With a surface, the two bars share the legend's
/// column, the volume's above. The caption sits on an opaque kCaptionBox. Never throws.
void annotate_frame(tsp::Image& img, const tsp::Camera& camera, tsp::Dims dims,
                    const tsp::TransferFunction& tf, int step, const std::optional<std::string>& time,
                    const std::string& field = "", const std::string& stretch = "",
                    const SurfaceLegend& surface = {});

/// Writes text at (x, y) (top-left, 1 pixel per font dot × scale) in colour rgb; characters
/// without a glyph are skipped. Never throws.
void draw_text(tsp::Image& img, int x, int y, const std::string& text, const unsigned char rgb[3],
               int scale = 1);

}  // namespace tspgl
