// Per-octree-node marks the traversal reads: where a node lies with respect to a clip solid
// (tsp/clip computes them) and where an LOD cut stops the spatial descent (tsp/lod computes
// them). Owned here so the traversal and its producers share one typed vocabulary.
#pragma once
#include <cstdint>
#include <span>

namespace tsp {

/// Where an octree node (or any box) lies with respect to a clip solid: wholly kept, wholly
/// removed (drawn nowhere), or across the clip surface (drawn textured and clipped per sample).
enum class ClipSide : std::uint8_t { kept = 0, removed = 1, straddles = 2 };

/// Where the spatial descent stops at an octree node: none (descend as usual), cut (the node is
/// in an LOD cut and draws its own level brick) or splat (the node is in the cut and is drawn
/// flat, its mean colour and opacity, never textured; tsp/lod/splat_cut.h).
enum class LodStop : std::uint8_t { none = 0, cut = 1, splat = 2 };

/// Per octree node, its ClipSide; empty: no clipping.
using ClipSides = std::span<const ClipSide>;

/// Per octree node, its LodStop; empty: stop at the leaves only.
using LodStops = std::span<const LodStop>;

}  // namespace tsp
