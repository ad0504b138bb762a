// Progressive refinement at full resolution (docs/player.md "No popping"): a picture is drawn
// again at full quality band by band — horizontal bands of kRefineBand rows, the middle of the
// view first, then outwards — each frame as many rows as the last frame's time per pixel says
// fit the frame-time target, over the picture already shown. GL-free: the renderer scissors its
// draws to the rectangles (VolumeRenderer::render with a PartialFrame).
#pragma once
#include <cstdint>
#include <vector>

#include "render/image_reuse.h"

namespace tspgl {

/// Rows per band of the progressive refinement.
inline constexpr int kRefineBand = 32;
/// Share of the picture the first frame of a refinement draws (no time per pixel known yet).
inline constexpr double kRefineFirstShare = 0.25;

/// The bands of one picture still to draw, handed out a frame's worth at a time.
class TileRefinement {
 public:
  /// Starts a width × height picture: every band to draw, the middle first. Never throws.
  void start(int width, int height);
  /// Forgets the picture (nothing to draw). Never throws.
  void stop();
  /// True between start() and the frame that drew the last band.
  bool active() const { return next_ < int(order_.size()); }
  /// True when started and every band was drawn.
  bool done() const { return !order_.empty() && !active(); }
  /// The next frame's rectangles: the next bands, as many rows as fit target_ms at the last
  /// frame's time per pixel (kRefineFirstShare of the picture at first), at least one band;
  /// adjacent bands merged. Empty when nothing is left. Never throws but bad_alloc.
  std::vector<PixelRect> next(double target_ms);
  /// The frame that drew the last next() took ms. Never throws.
  void drawn(double ms);
  /// True when the last next() handed out the last bands.
  bool last_handed_out() const { return handed_ > 0 && !active(); }
  /// Bands of the picture, and bands handed out so far.
  int bands() const { return int(order_.size()); }
  /// See bands().
  int bands_drawn() const { return next_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<int> order_;  // band indices (from the bottom), middle first
  int next_ = 0;            // the first band not handed out
  std::int64_t handed_ = 0; // pixels handed out by the last next()
  double ms_per_pixel_ = 0; // the last frames' time per pixel (0: unknown)
};

}  // namespace tspgl
