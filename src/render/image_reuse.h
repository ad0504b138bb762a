// Partial-image reuse (issue 9; after Shen et al. 1999's per-node sub-images): while the view,
// the TF and the knobs stay fixed — playing a series is exactly that — a pixel whose ray meets
// only bricks drawn exactly as in the previous frame keeps its colour, so only the screen
// rectangles of the bricks that changed are drawn again. A brick is unchanged when the frame
// draws it the same way: the same texture key (the span's representative step), the same flat
// node, or empty both times. GL-free: the renderer scissors its draws to the rectangles.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "tsp/frame/camera.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/tree/tsp_tree.h"

namespace tspgl {

/// A pixel rectangle [x0, x1) × [y0, y1), GL window coordinates (origin bottom left).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool operator==(const PixelRect&) const = default;
  /// Pixels covered.
  std::int64_t area() const { return std::int64_t(x1 - x0) * (y1 - y0); }
};

/// Per leaf brick, how a frame draws it: {0, 0} not at all; {kind and texture key, 0} from a
/// texture; {kind and node, the colour's bits} flat.
using BrickIdentities = std::vector<std::array<std::int64_t, 2>>;

/// How plan draws each leaf brick of tree, flat nodes in colour_of(TSP node id). level_pages,
/// when not empty, holds per leaf brick a tag of how a level brick covering it draws that page
/// (the renderer's full-resolution shading of the leaf); it becomes part of those leaves'
/// identity. Never throws.
BrickIdentities brick_identities(const tsp::TspTree& tree, const tsp::FramePlan& plan,
                                 const std::function<tsp::Rgba(int)>& colour_of,
                                 std::span<const std::int64_t> level_pages = {});

/// Edge in pixels of the tiles dirty regions are rounded out to.
inline constexpr int kReuseTile = 16;
/// Most rectangles a frame redraws; beyond it their bounding box is drawn instead.
inline constexpr int kMaxDirtyRects = 32;

/// The rectangles of a width × height image covering every brick whose identity differs between
/// before and now (their projected boxes, rounded out to kReuseTile tiles and merged into row
/// runs). Asserts both identity lists have one entry per brick. Never throws.
std::vector<PixelRect> dirty_rects(const tsp::TspTree& tree, const tsp::Camera& camera,
                                   const BrickIdentities& before, const BrickIdentities& now);

}  // namespace tspgl
